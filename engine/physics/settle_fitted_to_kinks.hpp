#pragma once
// Settling by projection with the rest surface's bends fitted (repose_kinks.hpp): the toe of
// a pile and the crest of a cut land on edges of the TIN instead of being smeared over the
// triangles across them.

#include "physics/material.hpp"
#include "physics/project_out_of_repose.hpp"
#include "physics/settle_by_projection.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// The projection's rho_per_area for fitting: half project_out_of_repose's default. The bends
/// are only where the projection has converged, and at the default the cone's toe was not
/// (r_S 1 cm: its worst direction 2.04 % too far out at the default, 1.60 % at this value, and
/// 1.59 % at a thousand times tighter residuals, 25 282 iterations); it takes twice the
/// iterations (7 175 against 3 535).
inline constexpr double kKinkFittingRhoPerArea = 0.05;

inline OutOfReposeOptions kink_fitting_region_options() {
    OutOfReposeOptions options;
    options.rho_per_area = kKinkFittingRhoPerArea;
    return options;
}

/// One fitting: vertices on the bends of `projected` (the projection of `input`, which was
/// gathered from `tin`), inserted on tin's surface as it still is, before the projection is
/// applied (Tin::insert_points_on_surface: the same sand). Returns the vertices added (0: no
/// bend, or every one within the snap distance of a vertex); the caller projects again.
std::size_t fit_projection_bends(Tin& tin, const ProjectionInput& input,
                                 const ReposeProjection& projected);

/// settle_by_projection over the whole terrain, in rounds: project (where it is out of
/// repose), find the bends of the projected surface, insert vertices there on the surface as
/// it is before the projection (Tin::insert_points_on_surface, so the sand and its volume
/// stay what they were), and project again from it. At most `rounds` fittings (>= 0; 0 is
/// settle_by_projection); the last projection is applied. The report's iterations and rounds
/// add up all the projections; fitted_vertices counts the vertices inserted. Throws
/// std::invalid_argument for rounds < 0, and as project_out_of_repose does.
ProjectionSettleReport settle_fitted_to_kinks(
    Tin& tin, const MaterialTable& materials, int rounds = 1,
    const ReposeProjectionOptions& options = {},
    const OutOfReposeOptions& region_options = kink_fitting_region_options());

}  // namespace sandtin
