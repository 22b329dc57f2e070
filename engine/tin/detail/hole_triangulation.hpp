#pragma once
// Private to engine/tin: the triangulation of the hole a patch removal leaves behind.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "geom/vec2.hpp"

namespace sandtin::detail {

/// Triangulates a simple polygon given counter-clockwise (interior on the left), with no points
/// added: the constrained Delaunay triangulation of its boundary, restricted to its interior.
/// Returns the n - 2 triangles as counter-clockwise triples of polygon indices, or an empty
/// vector when the polygon is not simple (repeated points, touching or crossing edges, a
/// boundary point on another edge) or is clockwise. Exact predicates; O(n log n), where the
/// ear clipping it replaces was quadratic to cubic in the hole's boundary length.
/// With `neighbours`, it also receives for each triangle, per corner i, the index of the
/// triangle across the edge opposite corner i, or -1 where that edge is on the polygon.
std::vector<std::array<std::size_t, 3>> triangulate_simple_polygon(
    std::span<const Vec2> polygon, std::vector<std::array<int, 3>>* neighbours = nullptr);

}  // namespace sandtin::detail
