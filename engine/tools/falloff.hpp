#pragma once
// Radial falloff of brushes and pours: weight 1 at the centre, 0 at the rim (t = r / radius).

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sandtin {

enum class Falloff : std::uint8_t {
    Constant,  ///< 1 everywhere inside the radius
    Linear,    ///< 1 - t
    Smooth,    ///< 1 - smoothstep(t): flat centre, soft rim
    Gaussian,  ///< exp(-4.5 t²): 1 % at the rim
};

inline double falloff_weight(Falloff f, double t) {
    if (!(t >= 0.0) || t > 1.0) return 0.0;
    switch (f) {
        case Falloff::Constant:
            return 1.0;
        case Falloff::Linear:
            return 1.0 - t;
        case Falloff::Smooth:
            return 1.0 - t * t * (3.0 - 2.0 * t);
        case Falloff::Gaussian:
            return std::exp(-4.5 * t * t);
    }
    return 0.0;
}

}  // namespace sandtin
