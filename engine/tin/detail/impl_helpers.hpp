#pragma once
// Private to engine/tin: argument checks and small geometry shared by the Tin translation
// units. CGAL-free.

#include <stdexcept>
#include <string>

#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin::detail {

/// Throws std::invalid_argument with `message` unless `condition` holds.
inline void require(bool condition, const char* message) {
    if (!condition) throw std::invalid_argument(message);
}

/// "(x, y)" with every digit, for error messages.
std::string describe(Vec2 p);

/// Throws std::invalid_argument, naming `what` and p, unless p is finite and inside `domain`.
void require_inside(const Rect& domain, Vec2 p, const char* what);

/// Signed area of the triangle a, b, c (positive when counter-clockwise), m².
inline double triangle_area(Vec2 a, Vec2 b, Vec2 c) {
    return 0.5 * cross(b - a, c - a);
}

/// Whether p lies within sqrt(snap2) of the line through a and b.
inline bool near_line(Vec2 a, Vec2 b, Vec2 p, double snap2) {
    const double c = cross(b - a, p - a);
    return c * c <= snap2 * length_squared(b - a);
}

}  // namespace sandtin::detail
