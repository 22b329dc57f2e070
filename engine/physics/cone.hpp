#pragma once
// The analytic rest state of sand poured at one point on flat ground: a cone whose flanks lie
// at the angle of repose. Volume V = pi R² h / 3 with R = h / tan(alpha) gives
// h = (3 V tan²(alpha) / pi)^(1/3).

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sandtin {

struct Cone {
    double height = 0.0;  ///< m
    double radius = 0.0;  ///< m
    double tan_alpha = 0.0;

    static Cone from_volume(double volume, double tan_alpha) {
        Cone c;
        c.tan_alpha = tan_alpha;
        c.height = std::cbrt(3.0 * volume * tan_alpha * tan_alpha / std::numbers::pi);
        c.radius = c.height / tan_alpha;
        return c;
    }
    /// Height above the ground at horizontal distance r from the apex (m).
    double surface(double r) const { return std::max(0.0, height - r * tan_alpha); }
};

}  // namespace sandtin
