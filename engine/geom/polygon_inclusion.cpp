#include "geom/polygon_inclusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

namespace {

// Below this many edges the whole-polygon test is as fast as the band look-up.
constexpr std::size_t kBandedMinimum = 24;

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
    if (n < kBandedMinimum) return;
    y_min_ = y_max_ = polygon[0].y;
    for (Vec2 v : polygon) {
        if (!std::isfinite(v.x) || !std::isfinite(v.y)) return;  // point_in_polygon decides
        y_min_ = std::min(y_min_, v.y);
        y_max_ = std::max(y_max_, v.y);
    }
    if (!(y_max_ > y_min_)) return;
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
