#pragma once
// nearest_edge for many points that only care about edges within a fixed reach (a ridge
// beside a tool's rim, a wall between two contours). A uniform grid lists in each cell the
// edges that come within the reach of it, in index order, so a query tests a handful of edges
// instead of the whole subdivided contour. Within the reach its answers are nearest_edge's,
// bit for bit (the same per-edge arithmetic, the same first-of-equals rule).

#include <cstdint>
#include <span>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/rect.hpp"

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
    Rect grid_;  ///< the cells' extent: the polygon's box grown by the reach
    double cells_per_metre_ = 0.0;
    std::uint32_t columns_ = 0;
    std::uint32_t rows_ = 0;
    // Cell c lists edges cell_edge_[cell_start_[c] .. cell_start_[c + 1]), ascending.
    std::vector<std::uint32_t> cell_start_;
    std::vector<std::uint32_t> cell_edge_;
};

}  // namespace sandtin
