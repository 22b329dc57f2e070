#pragma once
// The invariants a terrain must keep after every operation, checked by the stress runner:
// a valid constrained Delaunay triangulation (CGAL's own check), finite attributes everywhere
// (moisture in [0, 1], texture slide in [0, 1), bedrock never above the surface),
// constraints only from generations that were handed out (or 0, the terrain before the first
// stamp, which that stamp's fences guard), and vertex and constraint counts
// within the bounds a long session must respect.

#include <cstddef>
#include <optional>
#include <string>

#include "tin/tin.hpp"

namespace sandtin {

struct InvariantLimits {
    std::size_t max_vertices = 0;     ///< 0 = unbounded
    std::size_t max_constraints = 0;  ///< 0 = unbounded
};

/// Whether to run the triangulation's full validity check (Tin::check_valid: CGAL's structure,
/// the Delaunay property, ids, slots, lumped areas), which is O(n) and dominates a long
/// session's run time, or only the per-vertex and bookkeeping invariants.
enum class TriangulationCheck { full, skip };

struct InvariantViolation {
    std::string invariant;  ///< short name: "valid", "finite", "bedrock", "range",
                            ///< "valid", "generations", "bounded"
    std::string detail;
};

/// The first violated invariant, or nullopt. `next_generation` is the generation the next
/// stamp would get: every constraint must be older. O(n log n) for n vertices with the full
/// triangulation check, O(n) without it.
std::optional<InvariantViolation> check_terrain_invariants(
    const Tin& tin, Generation next_generation, const InvariantLimits& limits,
    TriangulationCheck triangulation = TriangulationCheck::full);

}  // namespace sandtin
