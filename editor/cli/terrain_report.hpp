#pragma once
// A terrain's statistics as JSON, shared by `info`, `demo` and `run`.

#include <nlohmann/json.hpp>

#include "tin/tin.hpp"

namespace sandtin::cli {

/// vertices, triangles, constrained_edges, constraints, volume (m³ above z = 0), bbox
/// ({min: [x, y, z], max: [x, y, z]} in metres), valid and, when invalid, problems.
nlohmann::json describe_terrain(const Tin& tin, bool validate = true);

}  // namespace sandtin::cli
