#pragma once
// Pairs the half-edges of a triangle soup with their twins, for rebuilding a triangulation
// from its list of triangles (a terrain loaded from a file). The half-edge opposite corner i of
// a counter-clockwise triangle runs from corner i + 1 to corner i + 2 (mod 3), CGAL's ccw(i)
// and cw(i); its twin runs the other way in the neighbouring triangle.
//
// Half-edges are grouped by the vertex they leave (a counting sort) and sorted by the vertex
// they reach, so a twin is a binary search among the few half-edges leaving one vertex. A hash
// table of every half-edge did the same job in 60 % of the time it took to load a
// 10^6-vertex scene, most of it allocating and freeing one node per half-edge.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace sandtin::detail {

enum class TwinProblem {
    None,
    RepeatedHalfEdge,  ///< two triangles hold the same oriented edge (overlap or duplicate)
    MissingTwin,       ///< an edge with one triangle only: the soup does not close up
    CornerOutOfRange,  ///< a corner not below the vertex count
};

/// Fills twin[3 t + i] = 3 u + j when the half-edge opposite corner i of triangle t is the twin
/// of the one opposite corner j of triangle u. Corners are numbered below `vertex_count`
/// (callers number a vertex at infinity like any other); 3 * triangles.size() must be below
/// 2^32. On a problem `twin` is unspecified.
/// O(h log d) for h half-edges and d the largest number of half-edges leaving one vertex.
TwinProblem pair_half_edges(std::span<const std::array<std::uint32_t, 3>> triangles,
                            std::uint32_t vertex_count, std::vector<std::uint32_t>& twin);

}  // namespace sandtin::detail
