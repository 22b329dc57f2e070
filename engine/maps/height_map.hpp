#pragma once
// CPU height-map bake: the TIN's piecewise-linear surface sampled on a map grid. The reference
// the GPU bake is tested against.

#include "maps/map_grid.hpp"
#include "tin/tin.hpp"

namespace sandtin {

/// One channel, heights in metres, exact to rounding (barycentric interpolation in the
/// containing triangle).
MapImage bake_height_map(const Tin& tin, const MapGrid& grid);

}  // namespace sandtin
