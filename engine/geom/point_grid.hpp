#pragma once
// "Is any of these points within r of p?" for many p against one fixed set of points: a
// uniform grid with cells r wide lists the points in each, so a query reads the 3 x 3 cells
// around p instead of the whole set.

#include <cstdint>
#include <span>
#include <vector>

#include "geom/rect.hpp"
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
    std::uint32_t cell(Vec2 p) const;

    double radius_ = 0.0;           ///< m
    double cells_per_metre_ = 0.0;  ///< at most 1 / radius
    Rect extent_;
    std::uint32_t columns_ = 0;
    std::uint32_t rows_ = 0;
    // Cell c holds points_[cell_start_[c] .. cell_start_[c + 1]).
    std::vector<std::uint32_t> cell_start_;
    std::vector<Vec2> points_;
};

}  // namespace sandtin
