#include "geom/near_edge_index.hpp"

#include "geom/grid_cell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandtin {

namespace {

/// Cells are about half the reach wide (an edge meets a few, a query's cell holds the edges
/// of about two reaches of contour), but never more than this many on a side, so a reach tiny
/// against the contour does not allocate a huge grid.
constexpr double kMaxCellsPerSide = 256.0;

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
    grid_ = box.inflated(margin);
    const double side = std::max(grid_.width(), grid_.height());
    cells_per_metre_ = std::min(2.0 / reach, kMaxCellsPerSide / side);
    columns_ = static_cast<std::uint32_t>(grid_.width() * cells_per_metre_) + 1;
    rows_ = static_cast<std::uint32_t>(grid_.height() * cells_per_metre_) + 1;
    const auto cell_range = [&](double lo, double hi, std::uint32_t count, double origin) {
        return std::pair{grid_cell(lo, origin, cells_per_metre_, count),
                         grid_cell(hi, origin, cells_per_metre_, count)};
    };
    // Two passes, counting then filling, so each cell's list is contiguous and ascending.
    cell_start_.assign(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::uint32_t> fill;
        if (pass == 1) {
            for (std::size_t c = 1; c < cell_start_.size(); ++c)
                cell_start_[c] += cell_start_[c - 1];
            cell_edge_.resize(cell_start_.back());
            fill.assign(cell_start_.begin(), cell_start_.end() - 1);
        }
        for (std::uint32_t i = 0; i < n; ++i) {
            const Vec2 a = polygon[i];
            const Vec2 b = polygon[(i + 1) % n];
            const auto [x0, x1] = cell_range(std::min(a.x, b.x) - margin,
                                             std::max(a.x, b.x) + margin, columns_, grid_.min.x);
            const auto [y0, y1] = cell_range(std::min(a.y, b.y) - margin,
                                             std::max(a.y, b.y) + margin, rows_, grid_.min.y);
            for (std::uint32_t y = y0; y <= y1; ++y) {
                for (std::uint32_t x = x0; x <= x1; ++x) {
                    const std::size_t c = static_cast<std::size_t>(y) * columns_ + x;
                    if (pass == 0)
                        ++cell_start_[c + 1];
                    else
                        cell_edge_[fill[c]++] = i;
                }
            }
        }
    }
}

NearestEdge NearEdgeIndex::nearest_within_reach(Vec2 p) const {
    if (cell_start_.empty()) return nearest_edge(p, polygon_);
    NearestEdgeSearch search(p, polygon_);
    if (!grid_.contains(p)) return search.result();  // beyond the reach of every edge (or NaN)
    const std::uint32_t column = grid_cell(p.x, grid_.min.x, cells_per_metre_, columns_);
    const std::uint32_t row = grid_cell(p.y, grid_.min.y, cells_per_metre_, rows_);
    const std::size_t c = static_cast<std::size_t>(row) * columns_ + column;
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
        search.offer(cell_edge_[k]);
    return search.result();
}

}  // namespace sandtin
