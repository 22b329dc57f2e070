#pragma once
// `sandtin bench import`: greedy insertion on the bay-hills Terrain-RGB tile at 10 m, 1 m and
// 0.2 m, and, when `node` and the npm package `delatin` are installed, delatin on the same
// heights in the same run. Delatin is found through $SANDTIN_DELATIN_DIR (its package folder),
// else through node's own module resolution from the working directory and the global folder.

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_import(const BenchConfig& config);

}  // namespace sandtin::bench
