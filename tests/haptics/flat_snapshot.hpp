#pragma once
// The snapshot the haptics-core tests feed the force loop: flat sand at one height under a
// 6-point tool of radius 3 cm centred at (0.5, 0.5) m. Core only (no TIN), so the tests built
// under ThreadSanitizer can use it; test_support.hpp is for the TIN-side tests.

#include <cmath>
#include <cstddef>

#include "haptics/haptic_snapshot.hpp"

namespace sandtin::haptics::test {

/// Flat sand at height `h` (m) under every control point and the centre.
inline HapticSnapshot flat_snapshot(double h = 0.0) {
    HapticSnapshot s;
    s.centre = {0.5, 0.5};
    s.centre_height = h;
    s.control_count = 6;
    for (std::size_t i = 0; i < 6; ++i) {
        const double a = 1.0471975511965976 * static_cast<double>(i);  // i * 60°
        s.control[i] = {0.5 + 0.03 * std::cos(a), 0.5 + 0.03 * std::sin(a)};
        s.control_height[i] = h;
    }
    return s;
}

}  // namespace sandtin::haptics::test
