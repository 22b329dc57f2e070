#include "geom/point_grid.hpp"

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
    const double side =
        std::max(radius, std::max(extent_.width(), extent_.height()) / kMaxCellsPerSide);
    columns_ = static_cast<std::uint32_t>(extent_.width() / side) + 1;
    rows_ = static_cast<std::uint32_t>(extent_.height() / side) + 1;
    cell_size_ = side;
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

std::uint32_t PointGrid::axis_cell(double x, double origin, std::uint32_t count) const {
    const double f = (x - origin) / cell_size_;
    if (!(f > 0.0)) return 0;
    if (!(f < static_cast<double>(count))) return count - 1;
    return std::min(static_cast<std::uint32_t>(f), count - 1);
}

std::uint32_t PointGrid::cell(Vec2 p) const {
    return axis_cell(p.y, extent_.min.y, rows_) * columns_ +
           axis_cell(p.x, extent_.min.x, columns_);
}

bool PointGrid::has_near(Vec2 p) const {
    if (columns_ == 0 || !(std::isfinite(p.x) && std::isfinite(p.y))) return false;
    // Points nearer than the radius lie in the cells that the box p ± radius meets (cells are
    // at least the radius wide, so at most 3 x 3 of them).
    const std::uint32_t x0 = axis_cell(p.x - radius_, extent_.min.x, columns_);
    const std::uint32_t x1 = axis_cell(p.x + radius_, extent_.min.x, columns_);
    const std::uint32_t y0 = axis_cell(p.y - radius_, extent_.min.y, rows_);
    const std::uint32_t y1 = axis_cell(p.y + radius_, extent_.min.y, rows_);
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
