#pragma once
// point_in_polygon for many points around one centre (a tool's footprint). Two shortcuts: a
// point nearer the centre than the polygon's nearest edge has the centre's answer, and one
// farther than its farthest vertex is outside. The points in the ring between test only the
// edges whose height range holds them, found through an index of horizontal bands: a
// non-convex contour (a letter, a foot) has its nearest edge close to the centre, so nearly
// every point lands in the ring, and a subdivided contour has hundreds of edges of which a
// horizontal line meets a handful. Same answers as point_in_polygon, border included.

#include <cstdint>
#include <span>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/rect.hpp"

namespace sandtin {

class PolygonInclusion {
  public:
    /// `polygon` must outlive this object.
    PolygonInclusion(std::span<const Vec2> polygon, Vec2 centre);

    bool contains(Vec2 p) const {
        const double d2 = length_squared(p - centre_);
        if (d2 < clear_squared_) return centre_inside_;
        if (d2 > reach_squared_) return false;
        if (band_start_.empty()) return point_in_polygon(p, polygon_);
        return banded_test(p);
    }

    /// True when an edge of the polygon touches the closed triangle abc. A triangle meets the
    /// region when a corner is inside (contains()) or this holds; the faces that meet a
    /// connected polygon form a connected set, so a walk over them reaches every vertex inside.
    bool border_meets_triangle(Vec2 a, Vec2 b, Vec2 c) const;

    std::span<const Vec2> polygon() const { return polygon_; }

  private:
    /// Band of height y: monotone in y, so an edge spanning [y_lo, y_hi] is listed in every
    /// band from band_of(y_lo) to band_of(y_hi), which includes band_of(y) for any y between.
    std::uint32_t band_of(double y) const {
        const double f = (y - y_min_) * bands_per_metre_;
        const auto last = static_cast<double>(band_start_.size() - 2);
        return static_cast<std::uint32_t>(f < last ? f : last);  // f >= 0 for y >= y_min_
    }
    bool banded_test(Vec2 p) const;

    std::span<const Vec2> polygon_;
    Vec2 centre_;
    bool centre_inside_ = false;
    double clear_squared_ = 0.0;
    double reach_squared_ = 0.0;
    Rect box_;  ///< the polygon's bounding box (empty when a vertex is not finite)
    // Band index (empty for small polygons, which point_in_polygon tests faster as a whole):
    // band b lists, in band_edge_[band_start_[b] .. band_start_[b + 1]), the edges (i, i - 1)
    // whose closed height range meets it.
    double y_min_ = 0.0;
    double y_max_ = 0.0;
    double bands_per_metre_ = 0.0;
    std::vector<std::uint32_t> band_start_;
    std::vector<std::uint32_t> band_edge_;
};

}  // namespace sandtin
