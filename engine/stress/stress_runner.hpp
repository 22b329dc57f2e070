#pragma once
// sandtin stress: a random mix of operations on a terrain, with the terrain invariants checked
// after every one. On the first failure the failing sequence is minimised (ddmin) into a short
// script that `sandtin run` replays.
//
// Invariants after every operation (see terrain_invariants.hpp for the structural ones):
//  - the terrain is finite, within bounds, with constraints from handed-out generations;
//  - the triangulation is valid (Tin::check_valid), after every operation by default, or
//    after every Nth, every save and the last one (StressOptions::full_check_every);
//  - volume accounting: the terrain's volume, recomputed from scratch, changed by what the
//    operation reported (erosion and simplification report zero: they conserve volume);
//  - a saved session loads back to the same terrain, byte for byte once re-encoded;
//  - an operation either is rejected cleanly when parsed (degenerate tools) or runs without
//    throwing.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stress/terrain_invariants.hpp"

namespace sandtin {

struct StressOptions {
    std::uint64_t seed = 1;
    std::size_t operations = 1000;
    std::size_t terrain_points = 3000;  ///< random points of the 1 m x 1 m starting terrain
    std::filesystem::path work_dir;     ///< where "save" operations write; a temporary one if empty
    /// The triangulation's full validity check (O(n), most of a long session's time) runs
    /// after every this many operations, after every save and after the last operation; the
    /// other invariants run after every operation. 1 checks everything every time. A replay
    /// while minimising a failure always checks every operation.
    std::size_t full_check_every = 1;
    bool minimise = true;
    double minimise_seconds = 120.0;
    /// Relative volume tolerance per operation: |ΔV - reported| <= tol * (|V| + |reported| +
    /// domain area x 1 m).
    double volume_tolerance = 1e-9;
    /// Vertex and constraint bounds; by default 4 x the starting vertices plus one vertex per
    /// (2 mm)² of domain, and 4096 constraints.
    std::optional<InvariantLimits> limits;
};

struct StressFailure {
    std::size_t operation = 0;  ///< 1-based index of the failing operation
    std::string invariant;      ///< "valid", "finite", "volume", "save_load", "exception", ...
    std::string detail;
    nlohmann::json script;  ///< the (minimised) script that reproduces the failure
    std::size_t script_operations = 0;
};

struct StressReport {
    std::uint64_t seed = 0;
    std::size_t operations_run = 0;
    std::size_t rejected = 0;  ///< operations the parser refused (degenerate tools)
    std::map<std::string, std::size_t> op_counts;
    std::map<std::string, double> op_seconds;  ///< wall time spent per operation kind
    /// Live vertex count sampled 20 times over the session: shows whether detail stays bounded.
    std::vector<std::size_t> vertex_trace;
    std::map<std::string, std::size_t> rejections;  ///< first line of each distinct message
    double seconds = 0.0;
    std::size_t full_checks = 0;  ///< operations after which the triangulation was fully checked
    std::size_t max_vertices = 0;
    std::size_t max_constraints = 0;
    std::size_t final_vertices = 0;
    double max_volume_residual = 0.0;  ///< largest relative volume residual seen
    std::optional<StressFailure> failure;

    nlohmann::json to_json() const;
};

/// Runs the session. `progress` (optional) is called after each operation with its index.
StressReport run_stress(const StressOptions& options,
                        const std::function<void(std::size_t)>& progress = {});

/// The script header (terrain and settings) a stress session starts from; with "operations"
/// added it is a script `sandtin run` accepts.
nlohmann::json stress_script_header(const StressOptions& options);

}  // namespace sandtin
