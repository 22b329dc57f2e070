#include "io/export_mesh_stl.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "io/byte_stream.hpp"

namespace sandtin {

std::vector<std::uint8_t> encode_stl(const ExportMesh& mesh) {
    if (mesh.triangles.size() > UINT32_MAX) {
        throw std::invalid_argument("STL export: more than 2^32 triangles");
    }
    ByteWriter w;
    std::array<std::uint8_t, 80> header{};
    // A header starting with "solid" makes some readers take the file for ASCII STL.
    const std::string text = "sandtin terrain (binary STL)";
    std::copy(text.begin(), text.end(), header.begin());
    w.put_bytes(header);
    w.put(static_cast<std::uint32_t>(mesh.triangles.size()));
    const auto put3 = [&](Vec3 v) {
        w.put(static_cast<float>(v.x));
        w.put(static_cast<float>(v.y));
        w.put(static_cast<float>(v.z));
    };
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        put3(triangle_normal(mesh, k));
        for (std::uint32_t v : mesh.triangles[k])
            put3(mesh.positions[v]);
        w.put<std::uint16_t>(0);
    }
    return std::move(w.bytes());
}

}  // namespace sandtin
