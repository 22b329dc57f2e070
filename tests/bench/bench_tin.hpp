#pragma once
// `sandtin bench tin`: the TIN core against raw CGAL, and restoring a terrain from its snapshot.

#include <nlohmann/json.hpp>

#include "bench_common.hpp"

namespace sandtin::bench {

nlohmann::json bench_tin(const BenchConfig& config);

}  // namespace sandtin::bench
