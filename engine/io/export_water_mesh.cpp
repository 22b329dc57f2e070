#include "io/export_water_mesh.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sandtin {

ExportMesh build_water_mesh(const Tin& tin, const MeshExportOptions& options, double min_depth) {
    if (!(std::isfinite(options.unit_scale) && options.unit_scale > 0.0))
        throw std::invalid_argument("water mesh export: the unit scale must be positive");
    ExportMesh mesh;
    mesh.up = options.up;
    mesh.unit_scale = options.unit_scale;
    const Rect d = tin.domain();
    mesh.domain = d;
    mesh.z_min = std::numeric_limits<double>::infinity();
    mesh.z_max = -std::numeric_limits<double>::infinity();
    const VertexArrays& va = tin.vertices();

    // The wet triangles, their corners numbered in first-use order (terrain frame).
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> index_of(va.size(), kUnused);
    std::vector<Vec3> points;
    const auto wet = [&](VertexId v) {
        return va.water_depth[v.index()] >= min_depth && va.water_depth[v.index()] > 0.0;
    };
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        if (!wet(t[0]) && !wet(t[1]) && !wet(t[2])) continue;
        std::array<std::uint32_t, 3> corners{};
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = t[static_cast<std::size_t>(k)].index();
            if (index_of[v] == kUnused) {
                index_of[v] = static_cast<std::uint32_t>(points.size());
                // A film below min_depth is the shore: the surface meets the bed there.
                const double z =
                    va.height[v] + (wet(t[static_cast<std::size_t>(k)]) ? va.water_depth[v] : 0.0);
                points.push_back({va.position[v].x, va.position[v].y, z});
                mesh.z_min = std::min(mesh.z_min, z);
                mesh.z_max = std::max(mesh.z_max, z);
            }
            corners[static_cast<std::size_t>(k)] = index_of[v];
        }
        mesh.triangles.push_back(corners);
    }
    if (points.empty()) {
        mesh.z_min = mesh.z_max = 0.0;
        return mesh;
    }
    mesh.surface_vertices = points.size();
    mesh.surface_triangles = mesh.triangles.size();

    // Area-weighted vertex normals of the water's own triangles.
    std::vector<Vec3> normals(points.size());
    for (const auto& t : mesh.triangles) {
        const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        for (std::uint32_t v : t)
            normals[v] += n;
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        mesh.positions.push_back(to_output_frame(points[i], options.up) * options.unit_scale);
        mesh.normals.push_back(
            to_output_frame(normalised(normals[i], {0.0, 0.0, 1.0}), options.up));
        mesh.uvs.push_back(map_uv(d, points[i]));
    }
    return mesh;
}

}  // namespace sandtin
