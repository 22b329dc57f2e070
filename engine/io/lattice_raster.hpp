#pragma once
// Exact scan conversion of a lattice triangle: for each lattice row, the columns of the
// lattice points inside the closed triangle. Integer arithmetic only, so a point on a shared
// edge belongs to both triangles and none is ever lost to rounding. Each edge is stepped row
// by row with a quotient and remainder (one division per edge, not per row): greedy import
// scans hundreds of thousands of small triangles, where per-row divisions dominated.

#include <algorithm>
#include <array>
#include <cstdint>

namespace sandtin {

namespace lattice_detail {

inline std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/// floor((n0 + k * step) / d) for k = 0, 1, 2, ... with d > 0.
class FloorStepper {
  public:
    FloorStepper() = default;
    FloorStepper(std::int64_t n0, std::int64_t step, std::int64_t d)
        : value_(floor_div(n0, d)),
          rem_(n0 - value_ * d),
          q_(floor_div(step, d)),
          r_(step - q_ * d),
          d_(d) {}
    std::int64_t value() const { return value_; }
    void next() {
        value_ += q_;
        rem_ += r_;
        if (rem_ >= d_) {
            rem_ -= d_;
            ++value_;
        }
    }

  private:
    std::int64_t value_ = 0;
    std::int64_t rem_ = 0;
    std::int64_t q_ = 0;
    std::int64_t r_ = 0;
    std::int64_t d_ = 1;
};

}  // namespace lattice_detail

/// Calls row(j, lo, hi) for every lattice row j of the closed triangle (x[k], y[k]) (counter-
/// clockwise, positive area) that holds lattice points, columns lo..hi inclusive.
template <class Row>
void for_each_lattice_span(const std::array<std::int64_t, 3>& x,
                           const std::array<std::int64_t, 3>& y, Row&& row) {
    using lattice_detail::FloorStepper;
    const std::int64_t xmin = std::min({x[0], x[1], x[2]});
    const std::int64_t xmax = std::max({x[0], x[1], x[2]});
    const std::int64_t ymin = std::min({y[0], y[1], y[2]});
    const std::int64_t ymax = std::max({y[0], y[1], y[2]});
    // Edge p -> q keeps the inside where dy * (i - p.x) <= dx * (j - p.y). Rising edges
    // (dy > 0) bound the row from the right, falling ones from the left; a horizontal edge of
    // a counter-clockwise triangle bounds nothing within the triangle's rows.
    std::array<FloorStepper, 3> right;
    std::array<FloorStepper, 3> left;
    std::array<std::int64_t, 3> right_x{};
    std::array<std::int64_t, 3> left_x{};
    std::size_t n_right = 0;
    std::size_t n_left = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t m = (k + 1) % 3;
        const std::int64_t dx = x[m] - x[k];
        const std::int64_t dy = y[m] - y[k];
        const std::int64_t n0 = dx * (ymin - y[k]);
        if (dy > 0) {
            // i <= p.x + floor(dx (j - p.y) / dy)
            right[n_right] = FloorStepper(n0, dx, dy);
            right_x[n_right++] = x[k];
        } else if (dy < 0) {
            // i >= p.x + ceil(dx (j - p.y) / dy) = p.x - floor(dx (j - p.y) / -dy)
            left[n_left] = FloorStepper(n0, dx, -dy);
            left_x[n_left++] = x[k];
        }
    }
    for (std::int64_t j = ymin; j <= ymax; ++j) {
        std::int64_t lo = xmin;
        std::int64_t hi = xmax;
        for (std::size_t k = 0; k < n_right; ++k) {
            hi = std::min(hi, right_x[k] + right[k].value());
            right[k].next();
        }
        for (std::size_t k = 0; k < n_left; ++k) {
            lo = std::max(lo, left_x[k] - left[k].value());
            left[k].next();
        }
        if (lo <= hi) row(j, lo, hi);
    }
}

}  // namespace sandtin
