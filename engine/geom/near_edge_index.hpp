#pragma once
// nearest_edge for many points that only care about edges within a fixed reach (a ridge
// beside a tool's rim, a wall between two contours). A uniform grid (geom/uniform_grid.hpp)
// lists in each cell the edges that come within the reach of it, in index order, so a query
// tests a handful of edges instead of the whole subdivided contour. Within the reach its answers
// are nearest_edge's, bit for bit (the same per-edge arithmetic, the same first-of-equals rule).

#include <cstdint>
#include <span>

#include "geom/polygon.hpp"
#include "geom/uniform_grid.hpp"

namespace sandtin {

class NearEdgeIndex {
  public:
    /// `polygon` (closed, at least one vertex) must outlive this object; reach > 0 in metres.
    NearEdgeIndex(std::span<const Vec2> polygon, double reach);

    /// nearest_edge(p, polygon) when that edge is nearer than the reach; otherwise an answer
    /// whose distance is at least the reach (+infinity when no edge comes near p's cell).
    NearestEdge nearest_within_reach(Vec2 p) const;

  private:
    std::span<const Vec2> polygon_;
    /// Over the polygon's box grown by the reach; no cells when the input is unusable.
    UniformGrid grid_;
    /// Per cell, the edges (edge i runs from vertex i to i + 1) that come within the reach of
    /// it, ascending.
    PackedCells<std::uint32_t> cell_edges_;
};

}  // namespace sandtin
