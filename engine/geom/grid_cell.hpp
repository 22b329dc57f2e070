#pragma once
// The cell of a uniform grid a coordinate falls in, along one axis: shared by the grid indexes
// (NearEdgeIndex, BoxGrid, PointGrid), so that filling a grid and querying it agree.

#include <algorithm>
#include <cstdint>

namespace sandtin {

/// floor((x - origin) * cells_per_metre) clamped into [0, count) (count > 0); NaN maps to 0.
/// Monotone in x, so two closed intervals that share a point share that point's cell.
inline std::uint32_t grid_cell(double x, double origin, double cells_per_metre,
                               std::uint32_t count) {
    const double f = (x - origin) * cells_per_metre;
    if (!(f > 0.0)) return 0;
    if (!(f < static_cast<double>(count))) return count - 1;
    return std::min(static_cast<std::uint32_t>(f), count - 1);
}

}  // namespace sandtin
