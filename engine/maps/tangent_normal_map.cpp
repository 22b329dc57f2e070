#include "maps/tangent_normal_map.hpp"

#include <cmath>
#include <stdexcept>

#include "maps/triangle_raster.hpp"
#include "maps/vertex_normals.hpp"

namespace sandtin {

MapImage bake_tangent_normal_map(const Tin& surface, const MapImage& world, const MapGrid& grid) {
    if (world.width != grid.width || world.height != grid.height || world.channels != 3 ||
        world.values.size() != grid.size() * 3) {
        throw std::invalid_argument("tangent normal map: the world map does not match the grid");
    }
    const std::vector<Vec3> normals = vertex_normals(surface);
    std::vector<Vec3> tangents(normals.size());
    for (std::size_t i = 0; i < normals.size(); ++i)
        tangents[i] = surface_tangent(normals[i], {0.0, 0.0, 1.0});
    MapImage map{grid.width, grid.height, 3, std::vector<double>(grid.size() * 3)};
    for_each_sample(
        surface, grid,
        [&](std::size_t i, const std::array<VertexId, 3>& t, const std::array<double, 3>& w) {
            Vec3 n_sum{};
            Vec3 t_sum{};
            for (std::size_t k = 0; k < 3; ++k) {
                n_sum += normals[t[k].index()] * w[k];
                t_sum += tangents[t[k].index()] * w[k];
            }
            const Vec3 n = normalised(n_sum);
            const Vec3 tangent = normalised(t_sum, surface_tangent(n, {0.0, 0.0, 1.0}));
            const Vec3 b = cross(n, tangent);
            const Vec3 d{world.values[3 * i], world.values[3 * i + 1], world.values[3 * i + 2]};
            // Solve [T B N] v = d (Cramer). The interpolated T need not be perpendicular to the
            // interpolated N, so this is not a plain projection; the viewer normalises the
            // result, so v's length is free and only its direction is kept.
            const double det = dot(tangent, cross(b, n));
            Vec3 v = std::abs(det) > 1e-12 ? Vec3{dot(d, cross(b, n)), dot(tangent, cross(d, n)),
                                                  dot(tangent, cross(b, d))} *
                                                 (1.0 / det)
                                           : Vec3{dot(d, tangent), dot(d, b), dot(d, n)};
            v = normalised(v);
            map.values[3 * i] = v.x;
            map.values[3 * i + 1] = v.y;
            map.values[3 * i + 2] = v.z;
        });
    return map;
}

}  // namespace sandtin
