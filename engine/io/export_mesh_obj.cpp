#include "io/export_mesh_obj.hpp"

#include <array>
#include <charconv>

namespace sandtin {

namespace {

/// Shortest round-trip decimal form, so a reader gets the exact float back.
void put(std::string& out, double v) {
    std::array<char, 32> buf{};
    const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), end);
}

void put(std::string& out, std::size_t v) {
    std::array<char, 24> buf{};
    const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), end);
}

}  // namespace

std::string encode_obj(const ExportMesh& mesh, const std::string& mtl_name) {
    std::string out;
    out.reserve(mesh.positions.size() * 96 + mesh.triangles.size() * 40);
    out += "# sandtin terrain: ";
    put(out, mesh.positions.size());
    out += " vertices, ";
    put(out, mesh.triangles.size());
    out += mesh.up == UpAxis::Y ? " triangles, Y up, " : " triangles, Z up, ";
    put(out, mesh.unit_scale);
    out += " units per metre\n";
    if (const std::string g = georeference_comment(mesh); !g.empty()) out += "# " + g + "\n";
    if (!mtl_name.empty()) out += "mtllib " + mtl_name + "\n";
    out += "o terrain\n";
    for (const Vec3& p : mesh.positions) {
        out += "v ";
        put(out, p.x);
        out += ' ';
        put(out, p.y);
        out += ' ';
        put(out, p.z);
        out += '\n';
    }
    for (const auto& uv : mesh.uvs) {
        out += "vt ";
        put(out, uv[0]);
        out += ' ';
        put(out, 1.0 - uv[1]);
        out += '\n';
    }
    for (std::size_t i = 0; i < mesh.surface_vertices; ++i) {
        const Vec3& n = mesh.normals[i];
        out += "vn ";
        put(out, n.x);
        out += ' ';
        put(out, n.y);
        out += ' ';
        put(out, n.z);
        out += '\n';
    }
    for (std::size_t k = mesh.surface_triangles; k < mesh.triangles.size(); ++k) {
        const Vec3 n = triangle_normal(mesh, k);
        out += "vn ";
        put(out, n.x);
        out += ' ';
        put(out, n.y);
        out += ' ';
        put(out, n.z);
        out += '\n';
    }
    if (!mtl_name.empty()) out += "usemtl sand\n";
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const auto& t = mesh.triangles[k];
        // OBJ indices are 1-based; walls and bottom use their face's normal.
        const std::size_t face_normal =
            k >= mesh.surface_triangles ? mesh.surface_vertices + (k - mesh.surface_triangles) + 1
                                        : 0;
        out += 'f';
        for (std::uint32_t v : t) {
            out += ' ';
            put(out, std::size_t{v} + 1);
            out += '/';
            put(out, std::size_t{v} + 1);
            out += '/';
            put(out, face_normal != 0 ? face_normal : std::size_t{v} + 1);
        }
        out += '\n';
    }
    return out;
}

std::string encode_mtl(const ObjMaterial& m) {
    std::string out = "# sandtin terrain material\nnewmtl sand\nKa 0 0 0\nKd ";
    put(out, m.colour.x);
    out += ' ';
    put(out, m.colour.y);
    out += ' ';
    put(out, m.colour.z);
    out += "\nKs 0 0 0\nNs 1\nillum 1\n";
    if (!m.albedo_texture.empty()) out += "map_Kd " + m.albedo_texture + "\n";
    // Blender and most tools read map_Bump as a tangent-space normal map.
    if (!m.normal_texture.empty()) out += "map_Bump " + m.normal_texture + "\n";
    return out;
}

}  // namespace sandtin
