#pragma once
// `sandtin bench history`: undo and redo of a stroke on a large terrain (issue 7 target:
// undo of a stroke on a 10^6-vertex TIN in <= 50 ms), and what an autosave after each costs
// the frame with the kept copy (io/session_keeper.hpp) against a whole snapshot.

#include <nlohmann/json.hpp>

#include "bench_common.hpp"
#include "io/progress.hpp"

namespace sandtin::bench {

/// `progress` hears the terrain's construction and each round of stroke, undo and redo.
nlohmann::json bench_history(const BenchConfig& config, const ProgressCallback& progress = {});

}  // namespace sandtin::bench
