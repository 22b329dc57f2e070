#pragma once
// Wall time since a steady-clock instant, in milliseconds: the one clock reading behind every
// stage timing the engine and the editor report.

#include <chrono>

namespace sandtin {

inline double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

}  // namespace sandtin
