#pragma once
// `sandtin bench history`: undo and redo of a stroke on a large terrain (issue 7 target:
// undo of a stroke on a 10^6-vertex TIN in <= 50 ms).

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_history(const BenchConfig& config);

}  // namespace sandtin::bench
