#pragma once
// CPU water-depth bake: the water standing on the TIN (VertexArrays::water_depth), sampled on
// a map grid by linear interpolation in the containing triangle, as the height map samples
// the surface.

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// One channel, metres of water, >= 0 (0 where the terrain is dry).
MapImage bake_water_depth_map(const Tin& tin, const MapGrid& grid);

}  // namespace sandtin
