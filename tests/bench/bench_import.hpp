#pragma once
// `sandtin bench import`: greedy insertion on the bay-hills Terrain-RGB tile at 10 m, 1 m and
// 0.2 m, and on rough fBm tiles made here (512² at 10 and 1 m, 2048² at 10 and 3 m: bay-hills
// is gentle, and issue 41 asks to lead on any terrain); and, when `node` and the npm package
// `delatin` are installed, delatin on the same heights in the same run, with the ratios and
// whether sandtin kept no more points and ran faster at every error. Delatin is found through
// $SANDTIN_DELATIN_DIR (its package folder), else through node's own module resolution from the
// working directory and the global folder.

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_import(const BenchConfig& config);

}  // namespace sandtin::bench
