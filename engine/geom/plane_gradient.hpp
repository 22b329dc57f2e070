#pragma once
// The gradient of the plane through three points: the slope of a triangle of a height field.

#include <algorithm>
#include <cmath>
#include <optional>

#include "geom/vec2.hpp"
#include "geom/vec3.hpp"

namespace sandtin {

/// ∇h (m/m) of the plane through a, b and c ((x, y, z) in metres), or nothing when the
/// triangle has no area in the plane: |twice its area| <= min_area_ratio x its longer edge
/// from a, squared (0: only an exactly degenerate triangle; a tolerance such as 1e-12 also
/// leaves out slivers whose gradient is rounding noise).
inline std::optional<Vec2> plane_gradient(const Vec3& a, const Vec3& b, const Vec3& c,
                                          double min_area_ratio = 0.0) {
    const double e1x = b.x - a.x, e1y = b.y - a.y, dz1 = b.z - a.z;
    const double e2x = c.x - a.x, e2y = c.y - a.y, dz2 = c.z - a.z;
    const double det = e1x * e2y - e1y * e2x;
    const double scale = std::max(e1x * e1x + e1y * e1y, e2x * e2x + e2y * e2y);
    if (!(std::abs(det) > min_area_ratio * scale)) return std::nullopt;
    // g . e1 = dz1, g . e2 = dz2 (Cramer's rule).
    return Vec2{(dz1 * e2y - dz2 * e1y) / det, (e1x * dz2 - e2x * dz1) / det};
}

}  // namespace sandtin
