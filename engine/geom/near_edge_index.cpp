#include "geom/near_edge_index.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

/// Cells are about half the reach wide (an edge meets a few, a query's cell holds the edges
/// of about two reaches of contour), but never more than this many on a side, so a reach tiny
/// against the contour does not allocate a huge grid.
constexpr double kMaxIndexCellsPerSide = 256.0;

}  // namespace

NearEdgeIndex::NearEdgeIndex(std::span<const Vec2> polygon, double reach) : polygon_(polygon) {
    const std::size_t n = polygon.size();
    Rect box = bounding_box(polygon);
    if (n == 0 || !(reach > 0.0) || !std::isfinite(reach) || box.empty() ||
        !std::isfinite(box.width()) || !std::isfinite(box.height()))
        return;  // no grid: every query falls back to the whole polygon
    // The margin covers rounding: an edge whose computed distance is below the reach lies,
    // exactly, within a hair more than the reach of p.
    const double margin = reach * (1.0 + 1e-9) + 1e-12 * std::max(box.width(), box.height());
    const Rect extent = box.inflated(margin);
    const double side = std::max(extent.width(), extent.height());
    grid_ = UniformGrid::with_cells_per_metre(extent,
                                              std::min(2.0 / reach, kMaxIndexCellsPerSide / side));
    if (!grid_.has_cells()) return;  // a density that overflows (a subnormal reach): no grid
    // Each edge is filed, in index order, in every cell its box grown by the margin covers.
    cell_edges_ = PackedCells<std::uint32_t>(grid_.cell_count(), [&](auto&& file) {
        for (std::uint32_t i = 0; i < n; ++i) {
            const Vec2 a = polygon[i];
            const Vec2 b = polygon[(i + 1) % n];
            const Rect edge_box{{std::min(a.x, b.x), std::min(a.y, b.y)},
                                {std::max(a.x, b.x), std::max(a.y, b.y)}};
            grid_.for_each_cell(grid_.span_of(edge_box.inflated(margin)),
                                [&](std::size_t c) { file(c, i); });
        }
    });
}

NearestEdge NearEdgeIndex::nearest_within_reach(Vec2 p) const {
    if (!grid_.has_cells()) return nearest_edge(p, polygon_);
    NearestEdgeSearch search(p, polygon_);
    // Beyond the grid's extent lies beyond the reach of every edge (or p is NaN).
    if (!grid_.extent().contains(p)) return search.result();
    for (const std::uint32_t i : cell_edges_[grid_.cell_of(p)])
        search.offer(i);
    return search.result();
}

}  // namespace sandtin
