#pragma once
// Wavefront OBJ + MTL. Positions, texture coordinates (v up, as OBJ expects) and normals: one
// normal per surface vertex, one per wall or bottom face (flat walls); one material "sand"
// whose textures, when named, are the albedo and normal-map PNGs written next to the OBJ.

#include <string>

#include "io/export_mesh.hpp"

namespace sandtin {

struct ObjMaterial {
    std::string albedo_texture;  ///< file name relative to the MTL, or empty
    std::string normal_texture;  ///< file name relative to the MTL, or empty
    Vec3 colour{0.84, 0.74, 0.55};
};

/// OBJ text; `mtl_name` is the MTL file name it refers to (empty: no material).
std::string encode_obj(const ExportMesh& mesh, const std::string& mtl_name);
std::string encode_mtl(const ObjMaterial& material);

}  // namespace sandtin
