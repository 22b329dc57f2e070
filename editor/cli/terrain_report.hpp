#pragma once
// A terrain's statistics as JSON, shared by `info`, `demo` and `run`.

#include <nlohmann/json.hpp>

#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin::cli {

/// vertices, triangles, constrained_edges, constraints, volume (m³ above z = 0), bbox
/// ({min: [x, y, z], max: [x, y, z]} in metres), valid and, when invalid, problems.
nlohmann::json describe_terrain(const Tin& tin, bool validate = true);

/// The faces against the angle of repose of their sand (physics/face_slopes.hpp, default
/// tolerance 1e-3): faces judged, rock faces, skipped slivers, steep faces, the slopes' area
/// (m²) and the share of it steeper than repose, and the steepest face's |∇h| / tan(alpha) and
/// centroid [x, y] (m).
nlohmann::json describe_slopes(const Tin& tin, const MaterialTable& materials);

}  // namespace sandtin::cli
