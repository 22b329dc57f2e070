#pragma once
// The projection of a height field onto the repose set: the surface closest to the given one
// (in the volume norm, sum of lumped area x squared height change) whose every triangle has
// |grad h| <= tan(alpha), on or above the bedrock, holding exactly the same volume.
//
// This is the critical-slope model in its continuum form (Prigozhin's variational sandpile):
// each time step of Barrett & Prigozhin's finite-element schemes is this projection, and a
// collapse (a pour, an over-steep stamp) is one of them. Local moves (face_kernel.hpp) stop at
// the first surface where every triangle is at rest, and on a collapse that surface is
// corrugated across the slope at the mesh scale, so the pile does not converge to the physical
// one as the mesh is refined (issue 39, measured). The projection has no such freedom: a plane
// steeper than repose becomes the plane at repose through its mean, a point pour the cone.
//
// Method: ADMM (Boyd et al. 2011) on the split h = y (bedrock), grad h = z per face:
//  - the height step solves (A (1 + rho [bedrock]) + rho K) h = rhs, K the piecewise-linear
//    stiffness matrix, factored once per rho (Eigen's sparse LDL^T), with the volume held by
//    a Lagrange multiplier (one extra solve per factorisation);
//  - the face step projects each face's gradient onto the disc of radius tan(alpha);
//  - the bedrock step clamps to the bedrock;
//  - rho is balanced between the primal and dual residuals every few iterations, with
//    over-relaxation 1.6.
// Each height step conserves the volume exactly (to rounding): the result's volume is the
// input's. The result is feasible to the tolerance; faces left a hair steeper than repose are
// for the local rule to finish (SandPhysics does).

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin {

struct ReposeProblem {
    std::span<const Vec2> position;                       ///< per vertex (m)
    std::span<const std::array<std::uint32_t, 3>> faces;  ///< vertex indices, either orientation
    /// Per face: tan(alpha) > 0. A face whose bedrock is steeper may stand as steep as its rock.
    std::span<const double> face_tan_alpha;
    /// Per vertex: a third of the areas of its faces (m²), as Tin::vertices().lumped_area.
    std::span<const double> area;
    std::span<const double> height;   ///< per vertex (m): the surface to project
    std::span<const double> bedrock;  ///< per vertex (m), <= height; empty: no bedrock
    /// Per vertex, nonzero: the height is kept (outside the region being settled); empty: none.
    std::span<const std::uint8_t> held;
};

struct ReposeProjectionOptions {
    /// Relative primal and dual residuals at which ADMM stops (> 0).
    double tolerance = 1e-4;
    /// ...and only once no face is steeper than its bound (1 + this) (>= 0). The residuals
    /// are norms: at 1e-4 they left single faces up to 0.7 % steep, for the local rule to
    /// finish in thousands of creeping iterations (11 876 on a cone at r_S 5 mm); below the
    /// local rule's rest tolerance (1e-4) it finds nothing to do. Measured on cones of 2 500
    /// and 10 000 vertices: 848 and 1 291 iterations instead of 845 and 1 109.
    double steepness_tolerance = 5e-5;
    int max_iterations = 20000;
    /// ADMM's penalty rho at the start, per m² of the free region (1/m² x m² of multiplier
    /// scale, > 0). Its best value is about a quarter of the settled pile's footprint: 0.05
    /// when the region is the whole terrain around a pile that covers a fifth of it (cones
    /// poured on 2 500 to 40 000 vertices: 845-1 429 iterations to 1e-4);
    /// project_out_of_repose, whose regions hug the pile, uses its own.
    double rho_per_area = 0.05;
    /// Hears the fraction of the work done, in [0, 1] and never decreasing: every
    /// kProgressInterval iterations, and 1 when the projection ends. The estimate is how far
    /// the residuals and the steepest face have come, on a log scale, from the first iteration
    /// to the tolerances (ADMM converges linearly), or the share of max_iterations if that is
    /// further. It may throw to stop the projection (a Cancel): the exception passes through
    /// and nothing is returned. Empty: not called, and nothing is computed for it.
    std::function<void(double fraction)> on_progress;
    static constexpr int kProgressInterval = 16;
};

struct ReposeProjection {
    std::vector<double> height;  ///< per vertex (m); held and faceless vertices unchanged
    int iterations = 0;
    int factorisations = 0;
    bool converged = false;
    std::size_t free_vertices = 0;
    std::size_t degenerate_faces = 0;  ///< faces of (near) zero area, left unconstrained
    double steepest_ratio = 0.0;       ///< max over constrained faces of |grad h| / bound
    double volume_change = 0.0;        ///< sum A (h - h0) (m³): rounding only
};

/// Projects `problem.height` onto the repose set. Throws std::invalid_argument when the spans'
/// sizes disagree, an index is out of range, a tan(alpha) is not positive and finite, or a
/// height lies below its bedrock or is not finite. Never modifies the inputs.
ReposeProjection project_onto_repose(const ReposeProblem& problem,
                                     const ReposeProjectionOptions& options = {});

}  // namespace sandtin
