#include "geom/point_grid.hpp"

#include <algorithm>
#include <cmath>

namespace sandtin {

namespace {

/// At most this many cells on a side: a radius tiny against the spread of the points gets
/// larger cells rather than a huge grid (queries then read more points per cell).
constexpr double kMaxPointCellsPerSide = 1024.0;

}  // namespace

PointGrid::PointGrid(std::span<const Vec2> points, double radius) {
    if (!(radius > 0.0) || !std::isfinite(radius)) return;
    Rect extent;
    std::size_t finite_count = 0;
    for (const Vec2 p : points) {
        if (!is_finite(p)) continue;
        extent.expand(p);
        ++finite_count;
    }
    if (extent.empty()) return;
    radius_ = radius;
    // Cells a hair wider than the radius, so that a point nearer than the radius to p lies in
    // p's cell or a neighbour of it whatever the rounding of the cell arithmetic.
    const double side = std::max(radius * (1.0 + 1e-9),
                                 std::max(extent.width(), extent.height()) / kMaxPointCellsPerSide);
    grid_ = UniformGrid::with_cells_per_metre(extent, 1.0 / side);
    if (!grid_.has_cells()) return;  // a density that overflows (a subnormal radius): no grid
    std::vector<Vec2> finite_points;
    if (finite_count < points.size()) {
        finite_points.reserve(finite_count);
        for (const Vec2 p : points) {
            if (is_finite(p)) finite_points.push_back(p);
        }
        points = finite_points;
    }
    std::vector<std::uint32_t> cell(points.size());  // at most 1024² cells
    for (std::size_t i = 0; i < points.size(); ++i)
        cell[i] = static_cast<std::uint32_t>(grid_.cell_of(points[i]));
    points_ = PackedCells<Vec2>(grid_.cell_count(), cell, points);
}

bool PointGrid::has_near(Vec2 p) const {
    if (!grid_.has_cells() || !is_finite(p)) return false;
    // Points nearer than the radius lie in p's cell or its neighbours (cells are wider than the
    // radius; a p outside the extent maps to a border cell, next to everything within reach).
    const double r2 = radius_ * radius_;
    return grid_.any_cell(grid_.grown(grid_.span_of(p), 1), [&](std::size_t c) {
        for (const Vec2 q : points_[c]) {
            if (length_squared(q - p) < r2) return true;
        }
        return false;
    });
}

}  // namespace sandtin
