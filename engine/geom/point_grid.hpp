#pragma once
// "Is any of these points within r of p?" for many p against one fixed set of points: a
// uniform grid (geom/uniform_grid.hpp) with cells r wide lists the points in each, so a query
// reads the 3 x 3 cells around p instead of the whole set.

#include <span>

#include "geom/uniform_grid.hpp"
#include "geom/vec2.hpp"

namespace sandtin {

class PointGrid {
  public:
    /// Indexes `points` (copied) for queries within `radius` metres (> 0 and finite; otherwise
    /// no point is ever near). Non-finite points are left out.
    PointGrid(std::span<const Vec2> points, double radius);

    /// True when some indexed point q has length_squared(p - q) < radius².
    bool has_near(Vec2 p) const;

  private:
    double radius_ = 0.0;  ///< m
    UniformGrid grid_;     ///< over the points' box, cells a hair wider than the radius
    PackedCells<Vec2> points_;
};

}  // namespace sandtin
