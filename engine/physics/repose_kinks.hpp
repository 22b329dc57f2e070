#pragma once
// Where a surface at repose bends onto gentler ground: the toe of a pile, the crest of a cut.
//
// A piecewise-linear surface carries such a bend only along its edges. Where no edge lies on
// it, the triangles across it average the slope and the ground, so the bend is smeared over a
// triangle's width: a projected cone at r_S 1 cm had its toe up to 1.6 % of R too far out
// after the projection had converged (issue 39 asks for 1.5 %). Vertices put on the bend and a
// second projection from the same sand (settle_fitted_to_kinks.hpp) brought it to 0.97 %.
//
// The bend along an edge from a vertex a on a slope at repose (one of its triangles is) to a
// vertex b on gentler ground (one of its triangles is gentle, none at repose): the point where
// the plane of a's steepest triangle meets the plane of b's gentlest one, when it lies well
// inside the edge and the two planes cross it at clearly different slopes.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin {

struct ReposeKinkOptions {
    /// A triangle is at repose when |grad h| >= (1 - this) tan(alpha) (>= 0).
    double at_repose = 0.01;
    /// A triangle is gentle when |grad h| <= this x tan(alpha) (in [0, 1)).
    double gentle = 0.5;
    /// The bend is kept only between these fractions of the edge from a (0 < near < 0.5), and
    /// no closer than this fraction of the edge to a bend already put beside a or b. At 0.15
    /// a toe vertex holding 0.3 mm of sand 6 mm before the ground kept its long triangle
    /// down to the ground (the cone's worst direction stayed at 1.47 %; at 0.05, 0.97 %).
    double near = 0.05;
};

/// The bends of `height` over the triangles `faces` (vertex indices into `position` and
/// `height`; `face_tan_alpha` per face, > 0), at most one per edge, in no particular order.
/// Faces of zero area are skipped. Throws std::invalid_argument when the spans' sizes disagree
/// or an index is out of range.
std::vector<Vec2> find_repose_kinks(std::span<const Vec2> position,
                                    std::span<const std::array<std::uint32_t, 3>> faces,
                                    std::span<const double> face_tan_alpha,
                                    std::span<const double> height,
                                    const ReposeKinkOptions& options = {});

}  // namespace sandtin
