#pragma once
// Radial falloff of brushes and pours: weight 1 at the centre, 0 at the rim (t = r / radius).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

namespace sandtin {

enum class Falloff : std::uint8_t {
    Constant,  ///< 1 everywhere inside the radius
    Linear,    ///< 1 - t
    Smooth,    ///< 1 - smoothstep(t): flat centre, soft rim
    Gaussian,  ///< exp(-4.5 t²): 1 % at the rim
};

/// The names scripts, settings and panels use, indexed by the enum's value.
inline constexpr std::array<const char*, 4> kFalloffNames = {"constant", "linear", "smooth",
                                                             "gaussian"};

inline const char* falloff_name(Falloff f) {
    return kFalloffNames[static_cast<std::size_t>(f)];
}

/// The falloff called `name` (one of kFalloffNames), or nothing.
inline std::optional<Falloff> falloff_named(std::string_view name) {
    for (std::size_t i = 0; i < kFalloffNames.size(); ++i) {
        if (name == kFalloffNames[i]) return static_cast<Falloff>(i);
    }
    return std::nullopt;
}

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
