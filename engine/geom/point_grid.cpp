#include "geom/point_grid.hpp"

#include "geom/grid_cell.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

/// At most this many cells on a side: a radius tiny against the spread of the points gets
/// larger cells rather than a huge grid (queries then read more points per cell).
constexpr double kMaxCellsPerSide = 1024.0;

}  // namespace

PointGrid::PointGrid(std::span<const Vec2> points, double radius) {
    if (!(radius > 0.0) || !std::isfinite(radius)) return;
    for (const Vec2 p : points) {
        if (std::isfinite(p.x) && std::isfinite(p.y)) extent_.expand(p);
    }
    if (extent_.empty()) return;
    radius_ = radius;
    // Cells a hair wider than the radius, so that a point nearer than the radius to p lies in
    // p's cell or a neighbour of it whatever the rounding of the cell arithmetic.
    const double side = std::max(radius * (1.0 + 1e-9),
                                 std::max(extent_.width(), extent_.height()) / kMaxCellsPerSide);
    columns_ = static_cast<std::uint32_t>(extent_.width() / side) + 1;
    rows_ = static_cast<std::uint32_t>(extent_.height() / side) + 1;
    cells_per_metre_ = 1.0 / side;
    // Counting sort by cell: each cell's points contiguous.
    std::vector<std::uint32_t> cell_of;
    cell_start_.assign(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
    for (const Vec2 p : points) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y))) continue;
        const std::uint32_t c = cell(p);
        cell_of.push_back(c);
        ++cell_start_[c + 1];
    }
    for (std::size_t c = 1; c < cell_start_.size(); ++c)
        cell_start_[c] += cell_start_[c - 1];
    points_.resize(cell_of.size());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    std::size_t k = 0;
    for (const Vec2 p : points) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y))) continue;
        points_[fill[cell_of[k++]]++] = p;
    }
}

std::uint32_t PointGrid::cell(Vec2 p) const {
    return grid_cell(p.y, extent_.min.y, cells_per_metre_, rows_) * columns_ +
           grid_cell(p.x, extent_.min.x, cells_per_metre_, columns_);
}

bool PointGrid::has_near(Vec2 p) const {
    if (columns_ == 0 || !(std::isfinite(p.x) && std::isfinite(p.y))) return false;
    // Points nearer than the radius lie in p's cell or its neighbours (cells are wider than the
    // radius; a p outside the extent maps to a border cell, next to everything within reach).
    const std::uint32_t cx = grid_cell(p.x, extent_.min.x, cells_per_metre_, columns_);
    const std::uint32_t cy = grid_cell(p.y, extent_.min.y, cells_per_metre_, rows_);
    const std::uint32_t x0 = cx > 0 ? cx - 1 : 0;
    const std::uint32_t x1 = std::min(cx + 1, columns_ - 1);
    const std::uint32_t y0 = cy > 0 ? cy - 1 : 0;
    const std::uint32_t y1 = std::min(cy + 1, rows_ - 1);
    const double r2 = radius_ * radius_;
    for (std::uint32_t y = y0; y <= y1; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * columns_;
        for (std::size_t c = row + x0; c <= row + x1; ++c) {
            for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
                if (length_squared(points_[k] - p) < r2) return true;
            }
        }
    }
    return false;
}

}  // namespace sandtin
