#include "io/export_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "maps/vertex_normals.hpp"

namespace sandtin {

namespace {

/// Position along the domain's border, counter-clockwise from the south-west corner, so
/// sorting border vertices by it walks the border in order.
double border_parameter(const Rect& d, Vec2 p) {
    const double w = d.width();
    const double h = d.height();
    if (p.y == d.min.y) return p.x - d.min.x;            // south, eastwards
    if (p.x == d.max.x) return w + (p.y - d.min.y);      // east, northwards
    if (p.y == d.max.y) return w + h + (d.max.x - p.x);  // north, westwards
    return 2.0 * w + h + (d.max.y - p.y);                // west, southwards
}

bool on_border(const Rect& d, Vec2 p) {
    return p.x == d.min.x || p.x == d.max.x || p.y == d.min.y || p.y == d.max.y;
}

}  // namespace

double unit_scale_of(const std::string& units) {
    if (units == "m") return 1.0;
    if (units == "cm") return 100.0;
    if (units == "mm") return 1000.0;
    if (units == "km") return 0.001;
    if (units == "in") return 1.0 / 0.0254;
    if (units == "ft") return 1.0 / 0.3048;
    throw std::invalid_argument("unknown unit '" + units + "' (use m, cm, mm, km, in or ft)");
}

ExportMesh build_export_mesh(const Tin& tin, const MeshExportOptions& options) {
    if (!(std::isfinite(options.unit_scale) && options.unit_scale > 0.0)) {
        throw std::invalid_argument("mesh export: the unit scale must be positive");
    }
    if (options.base != BaseKind::None &&
        !(std::isfinite(options.base_depth) && options.base_depth > 0.0)) {
        throw std::invalid_argument(
            "mesh export: the base depth must be a positive number of "
            "metres");
    }
    ExportMesh mesh;
    mesh.up = options.up;
    mesh.unit_scale = options.unit_scale;
    const Rect d = tin.domain();
    mesh.domain = d;
    const VertexArrays& va = tin.vertices();

    // Terrain-frame points first; the frame change comes last.
    std::vector<Vec3> points;
    std::vector<Vec3> normals;
    std::vector<std::uint32_t> index_of(va.size(), std::numeric_limits<std::uint32_t>::max());
    const std::vector<Vec3> vertex_normal = vertex_normals(tin);
    mesh.z_min = std::numeric_limits<double>::infinity();
    mesh.z_max = -std::numeric_limits<double>::infinity();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        index_of[v] = static_cast<std::uint32_t>(points.size());
        points.push_back({va.position[v].x, va.position[v].y, va.height[v]});
        normals.push_back(vertex_normal[v]);
        mesh.z_min = std::min(mesh.z_min, va.height[v]);
        mesh.z_max = std::max(mesh.z_max, va.height[v]);
    }
    mesh.surface_vertices = points.size();
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        mesh.triangles.push_back(
            {index_of[t[0].index()], index_of[t[1].index()], index_of[t[2].index()]});
    }
    mesh.surface_triangles = mesh.triangles.size();

    if (options.base != BaseKind::None) {
        mesh.bottom = mesh.z_min - options.base_depth;
        // The border vertices in counter-clockwise order: consecutive ones are the surface's
        // border edges, each traversed a -> b by its surface triangle.
        std::vector<std::uint32_t> ring;
        for (std::uint32_t i = 0; i < mesh.surface_vertices; ++i) {
            if (on_border(d, {points[i].x, points[i].y})) ring.push_back(i);
        }
        std::sort(ring.begin(), ring.end(), [&](std::uint32_t a, std::uint32_t b) {
            return border_parameter(d, {points[a].x, points[a].y}) <
                   border_parameter(d, {points[b].x, points[b].y});
        });
        std::vector<std::uint32_t> below(ring.size());
        for (std::size_t k = 0; k < ring.size(); ++k) {
            below[k] = static_cast<std::uint32_t>(points.size());
            points.push_back({points[ring[k]].x, points[ring[k]].y, mesh.bottom});
            normals.push_back({});
        }
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const std::size_t m = (k + 1) % ring.size();
            // The wall uses b -> a, the opposite of the surface's border edge.
            mesh.triangles.push_back({ring[m], ring[k], below[k]});
            mesh.triangles.push_back({ring[m], below[k], below[m]});
        }
        if (options.base == BaseKind::Solid) {
            // A fan from the bottom's centre: no sliver triangles along collinear border points.
            const auto centre = static_cast<std::uint32_t>(points.size());
            points.push_back({d.centre().x, d.centre().y, mesh.bottom});
            normals.push_back({});
            for (std::size_t k = 0; k < ring.size(); ++k) {
                const std::size_t m = (k + 1) % ring.size();
                mesh.triangles.push_back({centre, below[m], below[k]});
            }
        }
        // Base vertices: area-weighted normals of their (wall and bottom) triangles.
        for (std::size_t k = mesh.surface_triangles; k < mesh.triangles.size(); ++k) {
            const auto& t = mesh.triangles[k];
            const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
            for (std::uint32_t v : t) {
                if (v >= mesh.surface_vertices) normals[v] += n;
            }
        }
        for (std::size_t v = mesh.surface_vertices; v < normals.size(); ++v)
            normals[v] = normalised(normals[v], {0.0, 0.0, -1.0});
    }

    mesh.positions.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        mesh.positions.push_back(to_output_frame(points[i], options.up) * options.unit_scale);
        mesh.normals.push_back(to_output_frame(normals[i], options.up));
        mesh.uvs.push_back(map_uv(d, points[i]));
    }
    return mesh;
}

Vec3 triangle_normal(const ExportMesh& mesh, std::size_t k) {
    const auto& t = mesh.triangles[k];
    return face_normal(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
}

std::string georeference_comment(const ExportMesh& mesh) {
    const Georeference& g = mesh.georeference;
    if (!g.known) return {};
    std::ostringstream text;
    text.precision(17);
    text << "georeference: the terrain point (" << mesh.domain.min.x << ", " << mesh.domain.min.y
         << ") m lies at west " << g.west << ", south " << g.south;
    if (!g.horizontal_unit.empty()) text << " (" << g.horizontal_unit << ")";
    if (!g.crs.empty()) text << " in " << g.crs;
    std::string line = text.str();
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    return line;
}

}  // namespace sandtin
