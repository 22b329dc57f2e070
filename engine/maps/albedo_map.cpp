#include "maps/albedo_map.hpp"

#include <algorithm>
#include <stdexcept>

#include "maps/triangle_raster.hpp"

namespace sandtin {

MapImage bake_albedo_map(const Tin& tin, const MapGrid& grid, const MaterialColours& palette) {
    if (palette.colours.empty()) throw std::invalid_argument("albedo bake: empty palette");
    const VertexArrays& va = tin.vertices();
    auto colour = [&](VertexId v) {
        const std::size_t m =
            std::min<std::size_t>(va.material[v.index()], palette.colours.size() - 1);
        const double wet = static_cast<double>(va.moisture[v.index()]);
        return palette.colours[m] * (1.0 - (1.0 - palette.wet_factor) * wet);
    };
    MapImage map{grid.width, grid.height, 3, std::vector<double>(grid.size() * 3)};
    for_each_sample(
        tin, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            const Vec3 c = colour(t[0]) * w[0] + colour(t[1]) * w[1] + colour(t[2]) * w[2];
            map.values[3 * i] = std::clamp(c.x, 0.0, 1.0);
            map.values[3 * i + 1] = std::clamp(c.y, 0.0, 1.0);
            map.values[3 * i + 2] = std::clamp(c.z, 0.0, 1.0);
        });
    return map;
}

}  // namespace sandtin
