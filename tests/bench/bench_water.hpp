#pragma once
// `sandtin bench water`: the two water schemes (engine/water) against SWASHES's analytic
// solutions, error against CPU time over halvings of the spacing, and their cost per step on
// a rained-on terrain (issue 40, item 9):
//  - dam breaks on a 10 m strip (Ritter on a dry bed, Stoker on a wet one), for the virtual
//    pipes and the finite volumes at orders 1 and 2, with fitted orders of convergence;
//  - Thacker's planar surface in a paraboloid after one period;
//  - a lake at rest over a bumpy bed after 10⁴ steps (its largest speed and surface error);
//  - ms per step with rain on a slope, and a dry terrain's step;
//  - the editor's water (live_water.hpp) on a bowl: ms per frame with a nozzle held, the
//    seconds until the pond rests, and a frame after an edit far from it (it stays at rest);
//  - vertex-steps per second of the pipes on the CPU and the GPU at 10⁵ and 10⁶ vertices
//    (bench_water_throughput.hpp).

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_water(const BenchConfig& config);

}  // namespace sandtin::bench
