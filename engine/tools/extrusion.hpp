#pragma once
// Material pushing (seed 000 §7.3.3, seed 004 §3.4.4): the volume a stamp displaced is put back
// into a ridge just outside the tool. The seeds' ridge had a fixed height and lost material;
// here its height is solved so the deposited volume equals the displaced one exactly.
//
// Cross-section: a parabola 1 - (2s/w - 1)² over the band s in [0, w] outward from the outer
// contour, sampled at s = w/4, w/2, 3w/4 and closed at s = w. Along the contour the ridge is
// weighted by how deep the tool cut next to each control point (averaged along the contour over
// a quarter of the width either side: a ridge that wide cannot follow a cut that changes from one
// point to the next) and by the direction of motion: ahead gets the most, the sides a third,
// behind nothing (f = clamp((n·d + 1/2) / 1.5, 0, 1)).
// Every vertex in the band carries the ridge. Where the band lacks vertices (a sparse terrain)
// stations are inserted on the surface first: lines of four across the band, a quarter width
// apart along the contour, each station only where no vertex is within an eighth of the width.

#include <optional>
#include <span>

#include "tin/tin.hpp"

namespace sandtin {

struct RidgeReport {
    double deposited = 0.0;  ///< m³ added to the terrain
    std::size_t vertices_inserted = 0;
    std::size_t edges_fenced = 0;  ///< with a RidgeFence
};

/// On a coarse TIN (an imported elevation model, whose triangles are far wider than the tool)
/// raising a vertex in the band tilts triangles tens of metres long, and inserting stations
/// re-triangulates beyond it. With these values the band's outer edge (the contour offset by
/// the width) is first inserted at the surface's height and constrained, after the bent edges
/// around it are fenced (Tin::fence_bent_edges), so the ridge changes nothing past it.
struct RidgeFence {
    double tolerance = 0.0;     ///< m of bend above which an edge is fenced
    Generation generation = 0;  ///< of the fences and the band's edge
};

/// Deposits `volume` m³ (negative: takes it away) in a ridge of width `width` m outside the
/// counter-clockwise polygon `outer`, weighted per outer vertex by `cut_depth` (m) and the motion
/// direction. Where that weighting leaves no part of the band inside the domain (a tool in a
/// corner, moving into it) the direction alone weights it, and failing that every side alike:
/// the volume is deposited whenever any of the band lies in the domain.
RidgeReport deposit_ridge(Tin& tin, std::span<const Vec2> outer, std::span<const double> cut_depth,
                          std::optional<Vec2> motion, double width, double volume,
                          LocateHint* hint = nullptr, std::vector<VertexId>* touched = nullptr,
                          const RidgeFence* fence = nullptr);

}  // namespace sandtin
