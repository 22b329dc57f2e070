#pragma once
// The TIN as an exportable triangle mesh: the surface, optionally closed into a solid (walls
// down to a flat bottom, for 3D printing) or hung with a skirt (walls only, to hide cracks
// between tiles), in the output frame and units. The mesh writers (OBJ, PLY, STL, glTF) all
// start from this one mesh.
//
// Invariants: triangles are counter-clockwise seen from outside (surface normals point up);
// positions [0, surface_vertices) are the TIN's live vertices in VertexId order and triangles
// [0, surface_triangles) the TIN's triangles; with BaseKind::Solid every edge is shared by
// exactly two triangles in opposite directions (a closed 2-manifold).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geom/rect.hpp"
#include "geom/vec3.hpp"
#include "io/heightmap_raster.hpp"
#include "tin/tin.hpp"

namespace sandtin {

enum class UpAxis : std::uint8_t {
    Y,  ///< (x, y, z) terrain -> (x, z, -y): glTF, most game engines, OBJ for Blender
    Z,  ///< terrain frame as is: CAD, slicers, GIS
};

enum class BaseKind : std::uint8_t { None, Skirt, Solid };

struct MeshExportOptions {
    UpAxis up = UpAxis::Z;
    double unit_scale = 1.0;  ///< output units per metre (1000 for millimetres)
    BaseKind base = BaseKind::None;
    double base_depth = 1.0;  ///< metres from the lowest surface point down to the bottom
};

/// Output units per metre for "m", "cm", "mm", "km", "in", "ft"; throws std::invalid_argument
/// naming the accepted units otherwise.
double unit_scale_of(const std::string& units);

struct ExportMesh {
    std::vector<Vec3> positions;             ///< output frame and units
    std::vector<Vec3> normals;               ///< per position, output frame, unit length
    std::vector<std::array<double, 2>> uvs;  ///< u east, v down the image (row 0 north)
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::size_t surface_vertices = 0;
    std::size_t surface_triangles = 0;
    Rect domain;         ///< metres, terrain frame
    double z_min = 0.0;  ///< metres, lowest surface height
    double z_max = 0.0;
    double bottom = 0.0;  ///< metres, height of the base's bottom (when there is a base)
    UpAxis up = UpAxis::Z;
    double unit_scale = 1.0;
    /// Where `domain.min` lies in the coordinates of the file the terrain was imported from;
    /// OBJ and PLY headers name it in a comment (their vertices stay in the terrain frame).
    Georeference georeference;
};

/// The comment text naming a known georeference, one line, or "" when it is not known.
std::string georeference_comment(const ExportMesh& mesh);

/// A terrain-frame vector (x, y, z up) in the output frame: as is for Z-up, (x, z, -y) for
/// Y-up. Positions then take the unit scale; normals do not.
inline Vec3 to_output_frame(Vec3 p, UpAxis up) {
    return up == UpAxis::Z ? p : Vec3{p.x, p.z, -p.y};
}

/// The texture coordinates of a terrain point: u east across `domain`, v down from its north
/// edge (image rows), as the baked maps lay their texels.
inline std::array<double, 2> map_uv(const Rect& domain, Vec3 p) {
    return {(p.x - domain.min.x) / domain.width(), (domain.max.y - p.y) / domain.height()};
}

/// Throws std::invalid_argument for a non-positive or non-finite unit scale or base depth.
ExportMesh build_export_mesh(const Tin& tin, const MeshExportOptions& options);

/// Unit normal of triangle k of the mesh (output frame).
Vec3 triangle_normal(const ExportMesh& mesh, std::size_t k);

}  // namespace sandtin
