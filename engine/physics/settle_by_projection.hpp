#pragma once
// Settles a TIN's sand by projection onto the repose set (physics/repose_projection.hpp): the
// exact rest state of a collapse, where local moves leave a surface corrugated across the
// slope (issue 39). Use it on a surface that is out of repose (after a pour, a stamp, an
// import); on a surface already at rest it changes nothing.

#include <span>

#include "physics/material.hpp"
#include "physics/repose_projection.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// The settle margin of the relaxation that finishes a projection: none. The faces it finds
/// are a hair steeper than repose (the solver's tolerance); levelled 3 % below it (the default
/// margin) they dented the settled surface and set off a cascade (the cone's error floored at
/// 1e-4 m, 0.24 % of H, at r_S 5 mm).
inline constexpr double kSettleMarginAfterProjection = 0.0;

struct ProjectionSettleReport {
    int iterations = 0;
    bool converged = false;
    std::size_t free_vertices = 0;
    std::size_t moved_vertices = 0;    ///< heights written (journaled)
    std::size_t degenerate_faces = 0;  ///< faces of (near) zero area, left to the local rule
    double steepest_ratio = 0.0;       ///< max |grad h| / tan(alpha) after, over judged faces
    double volume_change = 0.0;        ///< m³, rounding only
};

/// Projects the heights of `tin` onto {|grad h| <= tan(alpha) on every triangle, h >= bedrock}
/// with the same volume. Each triangle's tan(alpha) is the mean of its corners' (material and
/// moisture, `materials`). When `region` is not empty, only its vertices move; the rest are
/// held as they are. Heights are written with Tin::set_height, so the change journal and the
/// GPU mirror see them; faces left a hair steeper than repose (the projection's tolerance) are
/// for the local rule: activate the moved vertices and relax. Throws std::invalid_argument for
/// a dead vertex in `region`.
ProjectionSettleReport settle_by_projection(Tin& tin, const MaterialTable& materials,
                                            std::span<const VertexId> region = {},
                                            const ReposeProjectionOptions& options = {});

}  // namespace sandtin
