#include "maps/height_map.hpp"

#include "maps/triangle_raster.hpp"

namespace sandtin {

MapImage bake_height_map(const Tin& tin, const MapGrid& grid) {
    return interpolate_per_vertex(tin, grid, tin.vertices().height);
}

}  // namespace sandtin
