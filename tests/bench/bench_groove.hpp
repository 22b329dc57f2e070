#pragma once
// `sandtin bench groove`: the seeds' groove experiment (seed 003 §5, seed 004 §5.4).

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_groove(const BenchConfig& config);

}  // namespace sandtin::bench
