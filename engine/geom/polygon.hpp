#pragma once
// Simple-polygon predicates in double precision. They decide which old constraints a tool
// releases and which vertices a footprint covers, where a rounding-level misjudgement on the
// boundary is harmless; the triangulation itself uses CGAL's exact predicates.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

/// Signed area in m²: positive for counter-clockwise vertex order.
double signed_area(std::span<const Vec2> polygon);
/// Length of the closed polygon's boundary (metres).
double polygon_perimeter(std::span<const Vec2> polygon);

/// Bounding box of the points.
Rect bounding_box(std::span<const Vec2> points);

/// True when p is inside the closed polygon (crossing-number rule; border counts as inside
/// within rounding). Works for non-convex polygons; the polygon is implicitly closed.
bool point_in_polygon(Vec2 p, std::span<const Vec2> polygon);

/// What one edge (a, b) contributes to point_in_polygon at p: p lies on it within rounding, the
/// rightward ray from p crosses it, or neither. Only an edge whose closed y-range holds p.y
/// can be anything but None, which lets an index of edges by height skip the others.
enum class EdgeTest : unsigned char { None, Crosses, OnBorder };
inline EdgeTest polygon_edge_test(Vec2 p, Vec2 a, Vec2 b) {
    // On the border (collinear with an edge and inside its box) counts as inside; the
    // tolerance is relative to the edge so it scales with the coordinates.
    if (p.x >= std::min(a.x, b.x) && p.x <= std::max(a.x, b.x) && p.y >= std::min(a.y, b.y) &&
        p.y <= std::max(a.y, b.y)) {
        const double c = cross(b - a, p - a);
        const double scale = std::abs(b.x - a.x) + std::abs(b.y - a.y);
        if (std::abs(c) <= 1e-12 * scale * (scale + std::abs(p.x) + std::abs(p.y)))
            return EdgeTest::OnBorder;
    }
    if ((a.y > p.y) != (b.y > p.y)) {
        const double x_cross = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
        if (p.x < x_cross) return EdgeTest::Crosses;
    }
    return EdgeTest::None;
}

/// True when the closed segments [a,b] and [c,d] share a point.
bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

/// True when the segment [a,b] touches the closed polygon region: an endpoint inside or a
/// crossing of the border.
bool segment_touches_polygon(Vec2 a, Vec2 b, std::span<const Vec2> polygon);

/// True when no two non-adjacent edges of the closed polygon intersect and it has >= 3
/// vertices with non-zero area.
bool is_simple_polygon(std::span<const Vec2> polygon);

/// Distance from p to the closed segment [a,b].
double distance_to_segment(Vec2 p, Vec2 a, Vec2 b);

/// The edge of a closed polygon nearest to p: edge `index` runs from vertex index to index + 1
/// (wrapping), its closest point is at parameter t in [0, 1], `distance` away (m). The first
/// of equally near edges wins; compared by squared distance, one square root in all. The
/// polygon must have at least one vertex.
struct NearestEdge {
    std::size_t index = 0;
    double t = 0.0;
    double distance = 0.0;
};
NearestEdge nearest_edge(Vec2 p, std::span<const Vec2> polygon);

/// The search inside nearest_edge, one offered edge at a time: NearEdgeIndex offers only the
/// edges of a grid cell, nearest_edge all of them, and both keep the first of equally near
/// edges, so their answers are the same bits.
class NearestEdgeSearch {
  public:
    NearestEdgeSearch(Vec2 p, std::span<const Vec2> polygon) : p_(p), polygon_(polygon) {}
    /// Considers edge i, from vertex i to vertex i + 1 (wrapping).
    void offer(std::size_t i) {
        const Vec2 a = polygon_[i];
        const Vec2 ab = polygon_[(i + 1) % polygon_.size()] - a;
        const double len2 = length_squared(ab);
        const double t = len2 > 0.0 ? std::clamp(dot(p_ - a, ab) / len2, 0.0, 1.0) : 0.0;
        const double d2 = length_squared(p_ - (a + ab * t));
        if (d2 < best2_) {
            best2_ = d2;
            best_.index = i;
            best_.t = t;
        }
    }
    /// The nearest edge offered; distance +infinity when none was.
    NearestEdge result() const {
        NearestEdge r = best_;
        r.distance = std::sqrt(best2_);
        return r;
    }

  private:
    Vec2 p_;
    std::span<const Vec2> polygon_;
    NearestEdge best_;
    double best2_ = std::numeric_limits<double>::infinity();
};

}  // namespace sandtin
