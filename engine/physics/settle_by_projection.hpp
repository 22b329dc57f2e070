#pragma once
// Settles a TIN's sand by projection onto the repose set (physics/repose_projection.hpp): the
// exact rest state of a collapse, where local moves leave a surface corrugated across the
// slope (issue 39). Use it on a surface that is out of repose (after a pour, a stamp, an
// import); on a surface already at rest it changes nothing.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

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
    /// With no region given: faces out of repose found, and projections run over growing
    /// regions around them (project_out_of_repose.hpp; 0: nothing was out of repose).
    std::size_t steep_faces = 0;
    int rounds = 0;
    /// settle_fitted_to_kinks: vertices put on the rest surface's bends (0 elsewhere).
    std::size_t fitted_vertices = 0;
};

/// What a projection of a TIN's sand reads, copied out of it (settle_by_projection's first
/// phase): it can be projected on a worker thread while the TIN goes on being drawn (the
/// editor's Settle exactly). Per vertex id (dead ids have no faces and are left alone).
struct ProjectionInput {
    std::vector<Vec2> position;                       ///< m
    std::vector<std::array<std::uint32_t, 3>> faces;  ///< the TIN's triangles
    std::vector<double> face_tan_alpha;  ///< mean of the corners' (material and moisture)
    std::vector<double> area;            ///< lumped areas (m²)
    std::vector<double> height;          ///< m
    std::vector<double> bedrock;         ///< m; -inf where there is none
    std::vector<std::uint8_t> held;      ///< empty, or nonzero outside the region
    std::vector<std::uint8_t> alive;

    /// The problem over these arrays (valid while this input lives).
    ReposeProblem problem() const {
        return {position, faces, face_tan_alpha, area, height, bedrock, held};
    }
};

/// Copies what the projection of `tin` reads. When `region` is not empty, only its vertices
/// are free. Throws std::invalid_argument for a dead vertex in `region`.
ProjectionInput gather_projection_input(const Tin& tin, const MaterialTable& materials,
                                        std::span<const VertexId> region = {});

/// Writes the heights `projected` (the projection of `input.problem()`) into `tin` with
/// Tin::set_heights, and reports what changed. Throws std::runtime_error, writing nothing,
/// when `tin` is no longer the terrain `input` was gathered from: a vertex born, died, moved
/// or changed height since, or the triangles changed in number.
ProjectionSettleReport apply_projection(Tin& tin, const ProjectionInput& input,
                                        const ReposeProjection& projected);

/// Projects the heights of `tin` onto {|grad h| <= tan(alpha) on every triangle, h >= bedrock}
/// with the same volume. Each triangle's tan(alpha) is the mean of its corners' (material and
/// moisture, `materials`). When `region` is not empty, only its vertices move; the rest are
/// held as they are. Otherwise the whole terrain is settled where it is out of repose
/// (project_out_of_repose.hpp: the same surface, at the cost of the disturbed part). Heights
/// are written with Tin::set_heights, so the change journal and the GPU mirror see them; faces
/// left a hair steeper than repose (the projection's tolerance) are for the local rule:
/// activate the moved vertices and relax. Throws std::invalid_argument for a dead vertex in
/// `region`. The three phases: gather_projection_input, the projection
/// (project_out_of_repose, or project_onto_repose over a region), apply_projection.
ProjectionSettleReport settle_by_projection(Tin& tin, const MaterialTable& materials,
                                            std::span<const VertexId> region = {},
                                            const ReposeProjectionOptions& options = {});

}  // namespace sandtin
