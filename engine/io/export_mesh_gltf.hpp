#pragma once
// glTF 2.0 through tinygltf: one mesh with POSITION, NORMAL, TANGENT and TEXCOORD_0, uint32
// indices, and a PBR material whose base colour and normal textures are embedded PNGs. Walls
// and the bottom of a base get their own vertices with flat normals. glTF is Y-up in metres
// by specification; the mesh must use UpAxis::Y.
//
// .gltf output is a single self-contained JSON file (buffer as a data URI); .glb is binary.
//
// Water (io/export_water_mesh.hpp), when given and not empty, is a second mesh and node named
// "water" with POSITION and NORMAL and a material of its own, "water": a blue-green base
// colour at alpha 0.55 with alphaMode BLEND, smooth (roughness 0.05) and double-sided, so that
// Blender and game engines import it as a separate, see-through object over the terrain.

#include <cstdint>
#include <vector>

#include "io/export_mesh.hpp"

namespace sandtin {

struct GltfTextures {
    std::vector<std::uint8_t> albedo_png;  ///< empty: no base colour texture
    std::vector<std::uint8_t> normal_png;  ///< empty: no normal texture
    /// Linear RGB base colour factor without an albedo texture (glTF's baseColorFactor).
    Vec3 base_colour{1.0, 1.0, 1.0};
};

/// Throws std::invalid_argument for a Z-up mesh and std::runtime_error when tinygltf fails.
std::vector<std::uint8_t> encode_gltf(const ExportMesh& mesh, const GltfTextures& textures,
                                      bool binary, const ExportMesh* water = nullptr);

}  // namespace sandtin
