#include "geom/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

double signed_area(std::span<const Vec2> polygon) {
    const std::size_t n = polygon.size();
    if (n < 3) return 0.0;
    double twice = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        twice += cross(polygon[i], polygon[(i + 1) % n]);
    }
    return 0.5 * twice;
}

Rect bounding_box(std::span<const Vec2> points) {
    Rect r;
    for (Vec2 p : points)
        r.expand(p);
    return r;
}

bool point_in_polygon(Vec2 p, std::span<const Vec2> polygon) {
    const std::size_t n = polygon.size();
    if (n < 3) return false;
    bool inside = false;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const EdgeTest t = polygon_edge_test(p, polygon[i], polygon[j]);
        if (t == EdgeTest::OnBorder) return true;
        if (t == EdgeTest::Crosses) inside = !inside;
    }
    return inside;
}

namespace {

int orientation_sign(Vec2 a, Vec2 b, Vec2 c) {
    const double o = cross(b - a, c - a);
    return (o > 0.0) - (o < 0.0);
}

bool on_segment(Vec2 a, Vec2 b, Vec2 p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

}  // namespace

bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const int o1 = orientation_sign(a, b, c);
    const int o2 = orientation_sign(a, b, d);
    const int o3 = orientation_sign(c, d, a);
    const int o4 = orientation_sign(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    if (o1 == 0 && on_segment(a, b, c)) return true;
    if (o2 == 0 && on_segment(a, b, d)) return true;
    if (o3 == 0 && on_segment(c, d, a)) return true;
    if (o4 == 0 && on_segment(c, d, b)) return true;
    return false;
}

bool segment_touches_polygon(Vec2 a, Vec2 b, std::span<const Vec2> polygon) {
    Rect seg;
    seg.expand(a);
    seg.expand(b);
    if (!seg.intersects(bounding_box(polygon))) return false;
    if (point_in_polygon(a, polygon) || point_in_polygon(b, polygon)) return true;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (segments_intersect(a, b, polygon[i], polygon[(i + 1) % n])) return true;
    }
    return false;
}

bool is_simple_polygon(std::span<const Vec2> polygon) {
    const std::size_t n = polygon.size();
    if (n < 3) return false;
    if (std::abs(signed_area(polygon)) <= 0.0) return false;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = polygon[i];
        const Vec2 b = polygon[(i + 1) % n];
        if (a == b) return false;
        for (std::size_t j = i + 1; j < n; ++j) {
            const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
            if (adjacent) continue;
            if (segments_intersect(a, b, polygon[j], polygon[(j + 1) % n])) return false;
        }
    }
    return true;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const double len2 = length_squared(ab);
    if (len2 <= 0.0) return distance(p, a);
    const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
    return distance(p, a + ab * t);
}

NearestEdge nearest_edge(Vec2 p, std::span<const Vec2> polygon) {
    NearestEdgeSearch search(p, polygon);
    for (std::size_t i = 0; i < polygon.size(); ++i)
        search.offer(i);
    return search.result();
}

double polygon_perimeter(std::span<const Vec2> polygon) {
    double sum = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i)
        sum += distance(polygon[i], polygon[(i + 1) % polygon.size()]);
    return sum;
}

}  // namespace sandtin
