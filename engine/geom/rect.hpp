#pragma once
// Axis-aligned rectangles in the plane (metres). Used for the terrain domain and bounding boxes.

#include <algorithm>
#include <limits>

#include "geom/vec2.hpp"

namespace sandtin {

struct Rect {
    Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

    static constexpr Rect from_size(double width, double height) {
        return Rect{{0.0, 0.0}, {width, height}};
    }
    constexpr double width() const { return max.x - min.x; }
    constexpr double height() const { return max.y - min.y; }
    constexpr bool empty() const { return !(min.x <= max.x && min.y <= max.y); }
    constexpr Vec2 centre() const { return (min + max) * 0.5; }
    /// Closed containment: points on the border are inside.
    constexpr bool contains(Vec2 p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y;
    }
    /// Whether the segment a-b runs along one of the sides: both ends exactly on it (as
    /// clipping to the rectangle leaves them).
    constexpr bool has_on_one_side(Vec2 a, Vec2 b) const {
        return (a.x == min.x && b.x == min.x) || (a.x == max.x && b.x == max.x) ||
               (a.y == min.y && b.y == min.y) || (a.y == max.y && b.y == max.y);
    }
    constexpr bool intersects(const Rect& o) const {
        return !(o.min.x > max.x || o.max.x < min.x || o.min.y > max.y || o.max.y < min.y);
    }
    void expand(Vec2 p) {
        min = {std::min(min.x, p.x), std::min(min.y, p.y)};
        max = {std::max(max.x, p.x), std::max(max.y, p.y)};
    }
    void expand(const Rect& r) {
        expand(r.min);
        expand(r.max);
    }
    Rect inflated(double margin) const {
        return Rect{{min.x - margin, min.y - margin}, {max.x + margin, max.y + margin}};
    }
    friend constexpr bool operator==(const Rect&, const Rect&) = default;
};

}  // namespace sandtin
