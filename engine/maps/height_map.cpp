#include "maps/height_map.hpp"

#include "maps/triangle_raster.hpp"

namespace sandtin {

MapImage bake_height_map(const Tin& tin, const MapGrid& grid) {
    MapImage map{grid.width, grid.height, 1, std::vector<double>(grid.size())};
    const std::vector<double>& h = tin.vertices().height;
    for_each_sample(
        tin, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            map.values[i] =
                w[0] * h[t[0].index()] + w[1] * h[t[1].index()] + w[2] * h[t[2].index()];
        });
    return map;
}

}  // namespace sandtin
