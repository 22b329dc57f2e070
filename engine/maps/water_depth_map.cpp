#include "maps/water_depth_map.hpp"

#include <algorithm>

#include "maps/triangle_raster.hpp"

namespace sandtin {

MapImage bake_water_depth_map(const Tin& tin, const MapGrid& grid) {
    MapImage map = interpolate_per_vertex(tin, grid, tin.vertices().water_depth);
    // The weights are barycentric, in [0, 1] up to rounding: clamp that rounding off 0.
    for (double& d : map.values)
        d = std::max(d, 0.0);
    return map;
}

}  // namespace sandtin
