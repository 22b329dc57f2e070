#pragma once
// Long-edge refinement: splits edges longer than a maximum length near a point at their
// midpoints, on the surface and volume-conserving, so long TIN edges never spoil a stamp or a
// brush (seed 000 §7.2, "prevention of long edges").

#include <cstddef>
#include <span>
#include <vector>

#include "tin/tin.hpp"

namespace sandtin {

/// Keeps points inserted on the surface from re-shaping it. Inserting a point re-triangulates
/// the faces whose circumcircles hold it; on a coarse, curved TIN (an imported elevation
/// model) that bends the surface metres away. Before each insertion the bent edges it would
/// remove are constrained (Tin::fence_bent_edges), so it only subdivides them.
struct SurfaceFence {
    double tolerance = 0.0;     ///< metres of bend above which an edge is fenced, any length
    Generation generation = 0;  ///< of the fences, so later footprints and expiry free them
};

/// The fence for a dab (brush or pour) of `radius` metres: bends above the smaller of 1 % of
/// the radius and the simplification tolerance are fenced, one generation older than the next
/// stamp's. Edges of any length: flipping a short edge re-shapes its whole quadrilateral, whose
/// other diagonal may be long.
SurfaceFence dab_fence(double radius, double simplify_tolerance, Generation next_generation);

/// Whether the TIN around a dab is coarse for it: fewer than 16 vertices in its disc before it
/// refines. Sand sculpted at the dab's scale has hundreds there and its re-triangulation is the
/// dab's own detail; an elevation model's triangles are as wide as the dab or wider.
bool coarse_for_dab(const Tin& tin, Vec2 centre, double radius, LocateHint* hint = nullptr);

/// Inserts `points` on the surface, fencing first when `fence` is given. Returns the number of
/// edges fenced.
std::size_t insert_points_fenced(Tin& tin, std::span<const Vec2> points, const SurfaceFence* fence,
                                 LocateHint* hint = nullptr);

/// Which of a dab's `disc` vertices it hands to the simplifier. Removing a vertex levels the
/// volume change over its ring; a ring vertex outside the refined disc would carry that onto
/// its long triangles, metres away on a coarse TIN. So on a terrain the dab had to fence
/// (`fenced`), only vertices at least one refinement `spacing` inside the disc, whose rings
/// lie in it; elsewhere (sand) all of them.
std::vector<VertexId> simplifiable_after_dab(const Tin& tin, std::span<const VertexId> disc,
                                             Vec2 centre, double radius, double spacing,
                                             bool fenced);

struct RefineResult {
    std::size_t inserted = 0;  ///< vertices
    std::size_t fenced = 0;    ///< edges constrained by the fence
};

/// Splits, round after round, every edge longer than `max_length` among the faces meeting the
/// disc (centre, radius), until none is left or `max_insertions` points were inserted. With a
/// fence, each round's midpoints are fenced before they go in.
RefineResult refine_long_edges(Tin& tin, Vec2 centre, double radius, double max_length,
                               LocateHint* hint = nullptr, std::size_t max_insertions = 200000,
                               EditReport* report = nullptr, const SurfaceFence* fence = nullptr);

}  // namespace sandtin
