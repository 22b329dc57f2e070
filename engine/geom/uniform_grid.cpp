#include "geom/uniform_grid.hpp"

#include <cmath>

namespace sandtin {

namespace {

/// A guard against a caller's density overflowing the cell indices, not a size to aim for:
/// the indexes keep their grids to a few hundred cells a side.
constexpr std::uint32_t kCellLimitPerSide = 65536;

/// floor(length * per_metre) + 1 cells, at most kCellLimitPerSide; one when that is NaN (an
/// infinite length at zero density).
std::uint32_t cells_along(double length, double per_metre) {
    const double f = length * per_metre;
    if (!(f >= 0.0)) return 1;
    if (!(f < static_cast<double>(kCellLimitPerSide))) return kCellLimitPerSide;
    return static_cast<std::uint32_t>(f) + 1;
}

}  // namespace

UniformGrid UniformGrid::with_cells_per_metre(const Rect& extent, double cells_per_metre) {
    UniformGrid g;
    if (extent.empty() || !std::isfinite(extent.min.x) || !std::isfinite(extent.min.y) ||
        !(cells_per_metre >= 0.0) || !std::isfinite(cells_per_metre))
        return g;
    g.extent_ = extent;
    g.columns_per_metre_ = cells_per_metre;
    g.rows_per_metre_ = cells_per_metre;
    g.columns_ = cells_along(extent.width(), cells_per_metre);
    g.rows_ = cells_along(extent.height(), cells_per_metre);
    return g;
}

UniformGrid UniformGrid::with_cell_count(const Rect& extent, std::uint32_t target_cells) {
    UniformGrid g;
    const double w = extent.width();
    const double h = extent.height();
    if (extent.empty() || !(w > 0.0) || !(h > 0.0) || !std::isfinite(w) || !std::isfinite(h) ||
        target_cells == 0)
        return g;
    const double target = static_cast<double>(target_cells);
    const double columns = std::clamp(std::round(std::sqrt(target * w / h)), 1.0, target);
    const double rows = std::clamp(std::round(target / columns), 1.0, target);
    g.extent_ = extent;
    g.columns_ = static_cast<std::uint32_t>(columns);
    g.rows_ = static_cast<std::uint32_t>(rows);
    g.columns_per_metre_ = columns / w;
    g.rows_per_metre_ = rows / h;
    return g;
}

}  // namespace sandtin
