#pragma once
// Which sides of the domain let water out (issue 40, item 2): each open side's border edges
// (edges of one face only, both ends on that side) give half their length to each end as its
// outflow width (VirtualPipes::set_outflow_width), or open that end's border to free outflow
// (ShallowWater::set_open_border). A closed side is a wall.

#include <vector>

#include "geom/rect.hpp"
#include "water/shallow_water.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

struct OpenSides {
    bool west = false;   ///< x = domain.min.x
    bool east = false;   ///< x = domain.max.x
    bool south = false;  ///< y = domain.min.y
    bool north = false;  ///< y = domain.max.y
};

/// Per vertex of `mesh`: the length of open border (m) it lets water out over, half of each
/// border edge (an edge of one face) with both ends on an open side of `domain`; a vertex lies
/// on a side within 1e-9 of the domain's larger extent. For the GPU water
/// (gpu/gpu_water.hpp set_outflow_widths) and open_borders.
std::vector<double> outflow_widths(const WaterMesh& mesh, Rect domain, OpenSides sides);

/// Sets the outflow width of every vertex of `water` from the open `sides` of `domain` (the
/// others are closed again); a vertex lies on a side within 1e-9 of the domain's larger
/// extent. Returns the open border's total length (m).
template <class Water>
double open_borders(Water& water, Rect domain, OpenSides sides);
extern template double open_borders(VirtualPipes&, Rect, OpenSides);
extern template double open_borders(ShallowWater&, Rect, OpenSides);

}  // namespace sandtin
