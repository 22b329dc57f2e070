#pragma once
// A minimal Wavefront OBJ reader: positions and faces (polygons are fan-triangulated; texture
// and normal indices are ignored). Enough for tool imprint meshes and export round-trip tests.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sandtin {

struct TriangleMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Parses OBJ text. Throws std::runtime_error naming `name` and the line for malformed input
/// (bad numbers, indices out of range, faces with fewer than three corners, non-finite values).
TriangleMesh parse_obj(std::string_view text, const std::string& name = "OBJ");
TriangleMesh read_obj(const std::filesystem::path& path);

}  // namespace sandtin
