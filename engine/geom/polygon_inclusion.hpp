#pragma once
// point_in_polygon for many points around one centre (a tool's footprint): a point nearer the
// centre than the polygon's nearest edge has the centre's answer, and one farther than its
// farthest vertex is outside, so only points in the ring between pay for the full test. Same
// answers as point_in_polygon, border included.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "geom/polygon.hpp"

namespace sandtin {

class PolygonInclusion {
  public:
    /// `polygon` must outlive this object.
    PolygonInclusion(std::span<const Vec2> polygon, Vec2 centre)
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
        const double margin =
            1e-9 * (1.0 + std::sqrt(reach) + std::abs(centre.x) + std::abs(centre.y));
        const double inner_radius = std::max(clear - margin, 0.0);
        const double outer_radius = std::sqrt(reach) + margin;
        clear_squared_ = inner_radius * inner_radius;
        reach_squared_ = outer_radius * outer_radius;
    }

    bool contains(Vec2 p) const {
        const double d2 = length_squared(p - centre_);
        if (d2 < clear_squared_) return centre_inside_;
        if (d2 > reach_squared_) return false;
        return point_in_polygon(p, polygon_);
    }

  private:
    std::span<const Vec2> polygon_;
    Vec2 centre_;
    bool centre_inside_ = false;
    double clear_squared_ = 0.0;
    double reach_squared_ = 0.0;
};

}  // namespace sandtin
