#pragma once
// `sandtin bench water`'s throughput rows (issue 40, performance): vertex-steps per second of
// the virtual pipes on the CPU (water/virtual_pipes.hpp, one thread) and on the GPU
// (gpu/gpu_water.hpp), on one wet terrain per size: a lake over a bumpy bed with a swell
// running through it, every vertex under water (the scheme's whole cost; a dry terrain costs
// nothing on either). On lavapipe the GPU figures are a CPU driver's: reported, not targets.

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandtin::bench {

/// One row per size in `vertices`: {"vertices", "cpu": {step_ms_median, vertex_steps_per_s},
/// "gpu": the same and the device, or {"unavailable": reason}}.
nlohmann::json water_throughput(const std::vector<std::size_t>& vertices, int steps);

}  // namespace sandtin::bench
