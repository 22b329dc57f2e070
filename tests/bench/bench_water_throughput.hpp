#pragma once
// `sandtin bench water`'s throughput rows (issue 40, performance): vertex-steps per second of
// the virtual pipes on the CPU (water/virtual_pipes.hpp, on one thread and on two, side by
// side, wall clock) and on the GPU
// (gpu/gpu_water.hpp), on one wet terrain per size: a lake over a bumpy bed with a swell
// running through it, every vertex under water (the scheme's whole cost; a dry terrain costs
// nothing on either). On lavapipe the GPU figures are a CPU driver's: reported, not targets.

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandtin::bench {

/// One row per size in `vertices`: {"vertices", "cpu": {step_ms_median, vertex_steps_per_s,
/// threads: 1}, "cpu_2_threads": the same and the speedup over "cpu", "gpu": the same and the
/// device, or {"unavailable": reason}}.
nlohmann::json water_throughput(const std::vector<std::size_t>& vertices, int steps);

}  // namespace sandtin::bench
