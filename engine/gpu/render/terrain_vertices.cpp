#include "gpu/render/terrain_vertices.hpp"

#include <algorithm>
#include <cmath>

#include "maps/vertex_normals.hpp"

namespace sandtin::render {

std::vector<TerrainVertex> build_terrain_vertices(const Tin& tin, const MaterialTable& materials,
                                                  std::span<const std::uint8_t> active) {
    const VertexArrays& va = tin.vertices();
    const std::vector<Vec3> normals = vertex_normals(tin);
    const Vec2 origin = tin.domain().centre();
    std::vector<TerrainVertex> out;
    out.reserve(tin.triangle_count() * 3);
    const float corner_bary[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (TriangleSlot slot = 0; slot < tin.slot_capacity(); ++slot) {
        const auto c = tin.slot_triangle(slot);
        if (!c[0].valid()) continue;
        const float mask = static_cast<float>(tin.slot_constraint_mask(slot));
        // Slope of the plane through the corners: |grad z|.
        const Vec2 p0 = va.position[c[0].index()], p1 = va.position[c[1].index()],
                   p2 = va.position[c[2].index()];
        const double z0 = va.height[c[0].index()], z1 = va.height[c[1].index()],
                     z2 = va.height[c[2].index()];
        const Vec2 e1 = p1 - p0, e2 = p2 - p0;
        const double det = cross(e1, e2);
        double slope = 0.0;
        if (det != 0.0) {
            const double gx = ((z1 - z0) * e2.y - (z2 - z0) * e1.y) / det;
            const double gy = ((z2 - z0) * e1.x - (z1 - z0) * e2.x) / det;
            slope = std::hypot(gx, gy);
        }
        double talus = 0.0;
        for (VertexId v : c)
            talus += materials.at(va.material[v.index()]).talus_slope(va.moisture[v.index()]);
        talus /= 3.0;
        const float slope_ratio = static_cast<float>(talus > 0.0 ? slope / talus : 0.0);
        for (int k = 0; k < 3; ++k) {
            const std::size_t i = c[static_cast<std::size_t>(k)].index();
            TerrainVertex t{};
            t.position[0] = static_cast<float>(va.position[i].x - origin.x);
            t.position[1] = static_cast<float>(va.position[i].y - origin.y);
            t.position[2] = static_cast<float>(va.height[i]);
            t.normal[0] = static_cast<float>(normals[i].x);
            t.normal[1] = static_cast<float>(normals[i].y);
            t.normal[2] = static_cast<float>(normals[i].z);
            const Material& m = materials.at(va.material[i]);
            // Moist sand is darker: up to 40 % at saturation.
            const float wet = 1.0f - 0.4f * std::clamp(va.moisture[i], 0.0f, 1.0f);
            for (int j = 0; j < 3; ++j) {
                t.albedo[j] = m.colour[j] * wet;
                t.barycentric[j] = corner_bary[k][j];
            }
            t.overlay[0] = mask;
            t.overlay[1] = slope_ratio;
            t.overlay[2] = va.bedrock[i] <= kNoBedrock
                               ? 0.0f
                               : static_cast<float>(std::max(0.0, va.height[i] - va.bedrock[i]));
            t.overlay[3] = i < active.size() && active[i] ? 1.0f : 0.0f;
            t.slide[0] = va.slide[i].x;
            t.slide[1] = va.slide[i].y;
            out.push_back(t);
        }
    }
    return out;
}

}  // namespace sandtin::render
