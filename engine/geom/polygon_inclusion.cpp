#include "geom/polygon_inclusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

namespace {

// Small polygons are tested whole: with one band per two edges, a band would hold most of them.
constexpr std::size_t kBandedMinimum = 8;

}  // namespace

PolygonInclusion::PolygonInclusion(std::span<const Vec2> polygon, Vec2 centre)
    : polygon_(polygon), centre_(centre) {
    centre_inside_ = point_in_polygon(centre, polygon);
    double clear = std::numeric_limits<double>::infinity();
    double reach = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        clear = std::min(
            clear, distance_to_segment(centre, polygon[i], polygon[(i + 1) % polygon.size()]));
        reach = std::max(reach, length_squared(polygon[i] - centre));
    }
    // Strictly inside the clear disc no border point is, so the answer is the centre's;
    // beyond the reach, outside. point_in_polygon counts points within ~1e-12 of the
    // coordinates' scale off an edge as on it (inside), so both radii keep a margin well
    // beyond that band.
    const double margin = 1e-9 * (1.0 + std::sqrt(reach) + std::abs(centre.x) + std::abs(centre.y));
    const double inner_radius = std::max(clear - margin, 0.0);
    const double outer_radius = std::sqrt(reach) + margin;
    clear_squared_ = inner_radius * inner_radius;
    reach_squared_ = outer_radius * outer_radius;

    const std::size_t n = polygon.size();
    for (Vec2 v : polygon) {
        if (!std::isfinite(v.x) || !std::isfinite(v.y)) {
            box_ = Rect();  // point_in_polygon decides every point
            return;
        }
        box_.expand(v);
    }
    y_min_ = box_.min.y;
    y_max_ = box_.max.y;
    if (n < kBandedMinimum || !(y_max_ > y_min_)) return;
    // About one band per two edges: a subdivided contour's edges are short, so each meets one
    // or two bands, and a band holds the few edges a horizontal line crosses there.
    const std::size_t bands = std::clamp<std::size_t>(n / 2, 4, 4096);
    bands_per_metre_ = static_cast<double>(bands) / (y_max_ - y_min_);
    band_start_.assign(bands + 1, 0);
    const auto edge_bands = [&](std::size_t i) {
        const Vec2 a = polygon[i];
        const Vec2 b = polygon[i == 0 ? n - 1 : i - 1];
        return std::pair{band_of(std::min(a.y, b.y)), band_of(std::max(a.y, b.y))};
    };
    for (std::size_t i = 0; i < n; ++i) {  // count, shifted by one for the prefix sum
        const auto [lo, hi] = edge_bands(i);
        for (std::uint32_t b = lo; b <= hi; ++b)
            ++band_start_[b + 1];
    }
    for (std::size_t b = 1; b < band_start_.size(); ++b)
        band_start_[b] += band_start_[b - 1];
    band_edge_.resize(band_start_.back());
    std::vector<std::uint32_t> fill(band_start_.begin(), band_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const auto [lo, hi] = edge_bands(i);
        for (std::uint32_t b = lo; b <= hi; ++b)
            band_edge_[fill[b]++] = static_cast<std::uint32_t>(i);
    }
}

namespace {

/// Closed triangle, either orientation.
bool in_triangle(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
    const double d1 = cross(b - a, p - a);
    const double d2 = cross(c - b, p - b);
    const double d3 = cross(a - c, p - c);
    return (d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0) || (d1 <= 0.0 && d2 <= 0.0 && d3 <= 0.0);
}

}  // namespace

bool PolygonInclusion::border_meets_triangle(Vec2 a, Vec2 b, Vec2 c) const {
    Rect t;
    t.expand(a);
    t.expand(b);
    t.expand(c);
    if (box_.empty() || !t.intersects(box_)) return false;
    // An edge that touches the triangle has a height range meeting the triangle's, so the
    // bands over the triangle's heights list every candidate.
    const std::size_t n = polygon_.size();
    const auto touches = [&](std::size_t i) {
        const Vec2 p = polygon_[i];
        const Vec2 q = polygon_[i == 0 ? n - 1 : i - 1];
        return in_triangle(p, a, b, c) || segments_intersect(p, q, a, b) ||
               segments_intersect(p, q, b, c) || segments_intersect(p, q, c, a);
    };
    if (band_start_.empty()) {
        for (std::size_t i = 0; i < n; ++i) {
            if (touches(i)) return true;
        }
        return false;
    }
    const std::uint32_t first = band_of(std::max(t.min.y, y_min_));
    const std::uint32_t last = band_of(std::min(t.max.y, y_max_));
    for (std::uint32_t band = first; band <= last; ++band) {
        for (std::uint32_t k = band_start_[band]; k < band_start_[band + 1]; ++k) {
            if (touches(band_edge_[k])) return true;
        }
    }
    return false;
}

bool PolygonInclusion::banded_test(Vec2 p) const {
    // Outside the height range no edge can cross or hold p, as point_in_polygon finds too
    // (and a NaN coordinate is outside).
    if (!(p.y >= y_min_ && p.y <= y_max_)) return false;
    const std::uint32_t band = band_of(p.y);
    const std::size_t n = polygon_.size();
    bool inside = false;
    for (std::uint32_t k = band_start_[band]; k < band_start_[band + 1]; ++k) {
        const std::uint32_t i = band_edge_[k];
        const EdgeTest t = polygon_edge_test(p, polygon_[i], polygon_[i == 0 ? n - 1 : i - 1]);
        if (t == EdgeTest::OnBorder) return true;
        if (t == EdgeTest::Crosses) inside = !inside;
    }
    return inside;
}

}  // namespace sandtin
