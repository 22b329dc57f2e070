#pragma once
// Terrain export: one call per output file, chosen by its extension, shared by the CLI's
// `export` and the editor's File menu.
//
//   .obj (+ .mtl, and the albedo and normal-map PNGs next to it), .ply, .stl, .gltf, .glb
//   .png  a 16-bit height map, or with map = "normal" / "albedo" an 8-bit RGB map, or with
//         map = "water" a 16-bit water-depth map
//   .exr  a float height map, or with map = "water" a float water-depth map
// A glTF of a terrain that holds water carries the water surface as a second mesh and node,
// "water", with a translucent material (io/export_water_mesh.hpp).
//
// Meshes can be closed into a solid or given a skirt, simplified to a maximum error first,
// written Y-up or Z-up and in other units. Every file is written atomically.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/export_mesh.hpp"
#include "io/export_palette.hpp"
#include "io/greedy_tin.hpp"
#include "io/progress.hpp"
#include "maps/albedo_map.hpp"
#include "maps/normal_map.hpp"

namespace sandtin {

enum class ExportFormat : std::uint8_t {
    Obj,
    Ply,
    Stl,
    Gltf,
    Glb,
    HeightPng,
    HeightExr,
    NormalPng,
    AlbedoPng,
    WaterPng,
    WaterExr,
};

/// The format for an output path; `map` picks what a .png holds ("height", "normal" or
/// "albedo", or "water" for .png and .exr). Throws std::invalid_argument naming the supported
/// extensions or maps.
ExportFormat export_format_for(const std::filesystem::path& path, const std::string& map = "");
const char* to_string(ExportFormat format);

struct ExportOptions {
    /// Default per format: Y for OBJ and glTF (what Blender and game engines expect), Z for
    /// PLY and STL (CAD and slicers). glTF must be Y-up.
    std::optional<UpAxis> up;
    std::string units = "m";  ///< m, cm, mm, km, in, ft (meshes only)
    BaseKind base = BaseKind::None;
    double base_depth = 1.0;  ///< metres below the lowest point
    /// Simplify first: greedy insertion over the terrain sampled every `cell_size`, so that
    /// the exported surface is within max_error metres of those samples.
    std::optional<double> max_error;
    /// Metres between height-map samples (and simplification samples). Default: map_size.
    std::optional<double> cell_size;
    /// Metres between rows of those samples when not `cell_size` (an oblong import grid).
    std::optional<double> cell_height;
    /// Height maps record it for re-import (where the terrain's south-west corner lies in
    /// the coordinates of the file it was imported from); `known` false: none.
    Georeference georeference;
    /// Samples along the longer side of maps, textures and the simplification raster when no
    /// cell size is given.
    std::uint32_t map_size = 1024;
    /// Metres per texel of normal and albedo maps and of mesh textures: the user's cell size
    /// (`--cell-size`), each side rounded to whole texels. Default: `map_size` texels along
    /// the longer side. (Kept apart from cell_size, which the import grid's default fills for
    /// height maps and re-meshes only.)
    std::optional<double> texel_size;
    bool textures = true;  ///< OBJ and glTF: bake and embed/write albedo and normal maps
    /// glTF: the water standing on the terrain as a second mesh (none when it is dry).
    bool water = true;
    NormalMode normal_mode = NormalMode::Smooth;
    /// Albedo maps and mesh materials: the scene's materials (`export_palette`).
    MaterialColours palette = export_palette(MaterialTable::presets());
};

struct ExportReport {
    ExportFormat format = ExportFormat::Obj;
    std::vector<std::filesystem::path> files;  ///< every file written, the main one first
    std::size_t vertices = 0;                  ///< meshes
    std::size_t triangles = 0;                 ///< meshes
    Vec3 min{};                                ///< mesh bounds in the output frame and units
    Vec3 max{};
    std::uint32_t map_width = 0;  ///< maps: samples; meshes: texture size
    std::uint32_t map_height = 0;
    Vec2 map_spacing{};        ///< metres between those samples: (columns, rows)
    double height_step = 0.0;  ///< 16-bit PNG: metres per grey level
    std::optional<GreedyStats> simplified;
    std::size_t water_vertices = 0;  ///< glTF: the water mesh's
    std::size_t water_triangles = 0;
    double ms = 0.0;
};

/// Writes `out` (and its companions). Throws std::invalid_argument for bad options and
/// std::runtime_error naming the file when writing fails; files already written stay.
/// `progress` (io/progress.hpp) hears each stage: simplification, the mesh, baking each map,
/// encoding and writing.
ExportReport export_terrain(const Tin& tin, const std::filesystem::path& out, ExportFormat format,
                            const ExportOptions& options = {},
                            const ProgressCallback& progress = {});

nlohmann::json to_json(const ExportReport& report);

}  // namespace sandtin
