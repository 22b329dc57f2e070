#include "maps/water_depth_map.hpp"

#include <algorithm>

#include "maps/triangle_raster.hpp"

namespace sandtin {

MapImage bake_water_depth_map(const Tin& tin, const MapGrid& grid) {
    MapImage map{grid.width, grid.height, 1, std::vector<double>(grid.size())};
    const std::vector<double>& d = tin.vertices().water_depth;
    for_each_sample(
        tin, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            // Weights are barycentric, in [0, 1] up to rounding: clamp that rounding off 0.
            map.values[i] = std::max(
                0.0, w[0] * d[t[0].index()] + w[1] * d[t[1].index()] + w[2] * d[t[2].index()]);
        });
    return map;
}

}  // namespace sandtin
