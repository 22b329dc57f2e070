#pragma once
// The projection onto the repose set (repose_projection.hpp) where the sand is out of repose
// only: a pour or a stamp on a large terrain settles in the neighbourhood it disturbed, at the
// cost of that neighbourhood, and a terrain already at rest costs one pass over its faces.
//
// Phases:
//  1. seed: the vertices of every face steeper than its bound (tan(alpha), or its rock's own
//     steepness where that is steeper) by more than the tolerance;
//  2. region: the seeds grown by a few rings of neighbours; the rest is held;
//  3. project the region, unless a bound on the room in it (the held vertices plus tan(alpha)
//     times the distance) shows it cannot hold its sand: then grow it first;
//  4. check: if the projection did not converge, or the settled sand presses against the
//     region's rim (a face between free and held vertices brought up to its bound), the pile
//     wants more room: grow the region (twice the rings) and project again from the input,
//     until it fits or covers the whole terrain.
// Where no rim face is pressed, the region's projection is the whole terrain's: outside the
// faces it holds at their bound, the projection leaves the heights as they are (the repose set
// is unchanged by adding a constant, so no volume is spread over the rest of the terrain).

#include <cstddef>

#include "physics/repose_projection.hpp"
#include "physics/settle_by_projection.hpp"

namespace sandtin {

struct OutOfReposeReport {
    std::size_t steep_faces = 0;    ///< faces out of repose in the input (the seeds' faces)
    int rounds = 0;                 ///< projections run (0: nothing was out of repose)
    int rings = 0;                  ///< rings around the seeds in the last round
    std::size_t free_vertices = 0;  ///< in the last round
    bool whole_terrain = false;     ///< the last round held nothing (beyond input.held)
};

struct OutOfReposeOptions {
    /// A face is out of repose above its bound times (1 + this) (>= 0). The local rule's rest
    /// tolerance: a surface it calls at rest is not projected again.
    double steepness_tolerance = 1e-4;
    int first_rings = 3;  ///< rings around the seeds in the first round (>= 1)
    /// The projection's rho_per_area in every round (> 0): the regions hug the settled pile,
    /// a few times its footprint, where the whole terrain's default (0.05) assumes five.
    double rho_per_area = 0.1;
};

/// Projects `input` onto the repose set where it is out of repose (see the phases above), with
/// the projection's `options` in each round. Progress (options.on_progress) covers all the
/// rounds, monotone; it may throw to stop. The result is per vertex of `input`, as
/// project_onto_repose's; with nothing out of repose, the input's heights, converged, with 0
/// iterations. Throws as project_onto_repose does on bad input.
ReposeProjection project_out_of_repose(const ProjectionInput& input,
                                       const ReposeProjectionOptions& options = {},
                                       const OutOfReposeOptions& region_options = {},
                                       OutOfReposeReport* report = nullptr);

}  // namespace sandtin
