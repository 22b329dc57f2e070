#include "maps/normal_map.hpp"

#include "maps/triangle_raster.hpp"
#include "maps/vertex_normals.hpp"

namespace sandtin {

MapImage bake_normal_map(const Tin& tin, const MapGrid& grid, NormalMode mode, double z_scale) {
    MapImage map{grid.width, grid.height, 3, std::vector<double>(grid.size() * 3)};
    const std::vector<Vec3> normals =
        mode == NormalMode::Smooth ? vertex_normals(tin, z_scale) : std::vector<Vec3>{};
    const VertexArrays& va = tin.vertices();
    auto point = [&](VertexId v) {
        const Vec2 p = va.position[v.index()];
        return Vec3{p.x, p.y, va.height[v.index()] * z_scale};
    };
    for_each_sample(
        tin, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            const Vec3 n =
                mode == NormalMode::Smooth
                    ? normalised(normals[t[0].index()] * w[0] + normals[t[1].index()] * w[1] +
                                 normals[t[2].index()] * w[2])
                    : face_normal(point(t[0]), point(t[1]), point(t[2]));
            map.values[3 * i] = n.x;
            map.values[3 * i + 1] = n.y;
            map.values[3 * i + 2] = n.z;
        });
    return map;
}

}  // namespace sandtin
