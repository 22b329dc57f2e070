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
    Rect extent;
    for (const Vec2 p : points) {
        if (is_finite(p)) extent.expand(p);
    }
    if (extent.empty()) return;
    radius_ = radius;
    // Cells a hair wider than the radius, so that a point nearer than the radius to p lies in
    // p's cell or a neighbour of it whatever the rounding of the cell arithmetic.
    const double side = std::max(radius * (1.0 + 1e-9),
                                 std::max(extent.width(), extent.height()) / kMaxCellsPerSide);
    grid_ = UniformGrid::with_cells_per_metre(extent, 1.0 / side);
    if (!grid_.has_cells()) return;  // a density that overflows (a subnormal radius): no grid
    points_ = PackedCells<Vec2>(grid_.cell_count(), [&](auto&& file) {
        for (const Vec2 p : points) {
            if (is_finite(p)) file(grid_.cell_of(p), p);
        }
    });
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
