#pragma once
// Vertices a rounding error apart (CGAL's crossings of nearly coincident old rims) cannot be
// merged, but they must share one height: a height step between them is a vertical sliver.

#include <span>

#include "tin/tin.hpp"

namespace sandtin {

/// For each given vertex and each neighbour closer than the TIN's snap distance, sets both to
/// the lower of their heights (`take_lower`) or the higher.
void equalise_slivers(Tin& tin, std::span<const VertexId> vertices, bool take_lower);

/// The same, but each cluster meets at its area-weighted mean height, which moves no volume:
/// for edits that conserve volume (the simplifier's compensation shifts).
void level_slivers_conserving(Tin& tin, std::span<const VertexId> vertices);

}  // namespace sandtin
