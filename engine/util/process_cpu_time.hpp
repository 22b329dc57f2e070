#pragma once
// CPU time of the whole process (every thread's, the Vulkan driver's included), for benchmarks
// and the editor's idle measurement.

#include <ctime>

namespace sandtin {

/// Seconds of CPU the process has used so far (CLOCK_PROCESS_CPUTIME_ID).
inline double process_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace sandtin
