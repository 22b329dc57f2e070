#include "io/export_mesh_ply.hpp"

#include <string>

#include "io/byte_stream.hpp"

namespace sandtin {

std::vector<std::uint8_t> encode_ply(const ExportMesh& mesh) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment sandtin terrain, " +
        std::string(mesh.up == UpAxis::Y ? "Y up" : "Z up") + ", " +
        std::to_string(mesh.unit_scale) + " units per metre\n" +
        (georeference_comment(mesh).empty() ? std::string()
                                            : "comment " + georeference_comment(mesh) + "\n") +
        "element vertex " + std::to_string(mesh.positions.size()) +
        "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty "
        "float ny\nproperty float nz\nproperty float s\nproperty float t\nelement face " +
        std::to_string(mesh.triangles.size()) +
        "\nproperty list uchar uint vertex_indices\nend_header\n";
    ByteWriter w;
    w.put_bytes({reinterpret_cast<const std::uint8_t*>(header.data()), header.size()});
    const auto f = [](double v) { return static_cast<float>(v); };
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        const Vec3& n = mesh.normals[i];
        for (float v : {f(p.x), f(p.y), f(p.z), f(n.x), f(n.y), f(n.z), f(mesh.uvs[i][0]),
                        f(1.0 - mesh.uvs[i][1])}) {
            w.put(v);
        }
    }
    for (const auto& t : mesh.triangles) {
        w.put<std::uint8_t>(3);
        for (std::uint32_t v : t)
            w.put(v);
    }
    return std::move(w.bytes());
}

}  // namespace sandtin
