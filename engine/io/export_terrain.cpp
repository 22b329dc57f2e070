#include "io/export_terrain.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "io/export_maps.hpp"
#include "io/export_mesh_gltf.hpp"
#include "io/export_mesh_obj.hpp"
#include "io/export_mesh_ply.hpp"
#include "io/export_mesh_stl.hpp"
#include "io/export_water_mesh.hpp"
#include "io/heightmap_raster.hpp"
#include "maps/height_map.hpp"
#include "maps/tangent_normal_map.hpp"
#include "maps/water_depth_map.hpp"
#include "util/atomic_file.hpp"
#include "util/elapsed_ms.hpp"
#include "util/lower_extension.hpp"

namespace sandtin {

namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kMaxMapSide = 16384;

std::uint32_t samples_along(double length, double cell) {
    const double n = std::round(length / cell) + 1.0;
    if (!(n <= kMaxMapSide)) {
        std::ostringstream what;
        what << "export: a cell size of " << cell << " m gives more than " << kMaxMapSide
             << " samples along a " << length << " m side";
        throw std::invalid_argument(what.str());
    }
    return std::max<std::uint32_t>(2, static_cast<std::uint32_t>(n));
}

/// A grid of samples on the domain's corners and edges, as square as the domain allows.
MapGrid corner_grid(const Rect& d, const ExportOptions& o) {
    if (o.cell_size && !(std::isfinite(*o.cell_size) && *o.cell_size > 0.0)) {
        throw std::invalid_argument("export: the cell size must be a positive number of metres");
    }
    if (o.map_size < 2 || o.map_size > kMaxMapSide) {
        throw std::invalid_argument("export: the map size must lie in 2.." +
                                    std::to_string(kMaxMapSide));
    }
    if (o.cell_height && !(o.cell_size && std::isfinite(*o.cell_height) && *o.cell_height > 0.0)) {
        throw std::invalid_argument(
            "export: a row spacing needs a cell size, and both must be positive numbers of metres");
    }
    const double cell = o.cell_size.value_or(std::max(d.width(), d.height()) / (o.map_size - 1));
    return MapGrid(d, samples_along(d.width(), cell),
                   samples_along(d.height(), o.cell_height.value_or(cell)), SampleAt::Corners);
}

/// Texels covering the domain: texel_size metres each when given, each side rounded to whole
/// texels; map_size along the longer side otherwise.
MapGrid texture_grid(const Rect& d, const ExportOptions& o) {
    if (o.texel_size && !(std::isfinite(*o.texel_size) && *o.texel_size > 0.0)) {
        throw std::invalid_argument("export: the cell size must be a positive number of metres");
    }
    if (!o.texel_size && (o.map_size < 1 || o.map_size > kMaxMapSide)) {
        throw std::invalid_argument("export: the map size must lie in 1.." +
                                    std::to_string(kMaxMapSide));
    }
    const double longer = std::max(d.width(), d.height());
    const auto along = [&](double side) {
        const double n = std::max(
            1.0, std::round(o.texel_size ? side / *o.texel_size : o.map_size * side / longer));
        if (!(n <= kMaxMapSide)) {
            std::ostringstream what;
            what << "export: a cell size of " << *o.texel_size << " m gives more than "
                 << kMaxMapSide << " texels along a " << side << " m side";
            throw std::invalid_argument(what.str());
        }
        return static_cast<std::uint32_t>(n);
    };
    return MapGrid(d, along(d.width()), along(d.height()), SampleAt::Centres);
}

/// The terrain re-meshed by greedy insertion within max_error of its samples on `grid`.
GreedyResult simplify(const Tin& tin, const MapGrid& grid, double max_error,
                      const ProgressCallback& progress) {
    HeightRaster raster;
    raster.width = grid.width;
    raster.height = grid.height;
    const Vec2 spacing = grid.spacing();
    raster.cell_size = spacing.x;
    if (spacing.y != spacing.x) raster.cell_height = spacing.y;
    raster.origin = grid.domain.min;
    raster.heights = bake_height_map(tin, grid).values;
    raster.source_format = "tin";
    // The raster's domain is the TIN's up to the rounding of (n - 1) * cell.
    return greedy_tin(raster, {max_error, 0}, progress);
}

void write(const fs::path& p, std::span<const std::uint8_t> bytes, ExportReport& report) {
    write_file_atomically(p, bytes, {});
    report.files.push_back(p);
}

bool is_mesh(ExportFormat f) {
    return f == ExportFormat::Obj || f == ExportFormat::Ply || f == ExportFormat::Stl ||
           f == ExportFormat::Gltf || f == ExportFormat::Glb;
}

}  // namespace

ExportFormat export_format_for(const fs::path& path, const std::string& map) {
    const std::string ext = lower_extension(path);
    if (!map.empty() && ext != ".png" && !(ext == ".exr" && (map == "height" || map == "water"))) {
        throw std::invalid_argument(
            "export: --map applies to .png (and 'height' and 'water' to .exr), not '" + ext + "'");
    }
    if (ext == ".obj") return ExportFormat::Obj;
    if (ext == ".ply") return ExportFormat::Ply;
    if (ext == ".stl") return ExportFormat::Stl;
    if (ext == ".gltf") return ExportFormat::Gltf;
    if (ext == ".glb") return ExportFormat::Glb;
    if (ext == ".exr") return map == "water" ? ExportFormat::WaterExr : ExportFormat::HeightExr;
    if (ext == ".png") {
        if (map.empty() || map == "height") return ExportFormat::HeightPng;
        if (map == "normal") return ExportFormat::NormalPng;
        if (map == "albedo") return ExportFormat::AlbedoPng;
        if (map == "water") return ExportFormat::WaterPng;
        throw std::invalid_argument("export: unknown map '" + map +
                                    "' (use height, normal, albedo or water)");
    }
    throw std::invalid_argument("export: unknown output type '" + ext +
                                "' (use .obj, .ply, .stl, .gltf, .glb, .png or .exr)");
}

const char* to_string(ExportFormat f) {
    switch (f) {
        case ExportFormat::Obj:
            return "obj";
        case ExportFormat::Ply:
            return "ply";
        case ExportFormat::Stl:
            return "stl";
        case ExportFormat::Gltf:
            return "gltf";
        case ExportFormat::Glb:
            return "glb";
        case ExportFormat::HeightPng:
            return "height-png";
        case ExportFormat::HeightExr:
            return "height-exr";
        case ExportFormat::NormalPng:
            return "normal-png";
        case ExportFormat::AlbedoPng:
            return "albedo-png";
        case ExportFormat::WaterPng:
            return "water-png";
        case ExportFormat::WaterExr:
            return "water-exr";
    }
    return "?";
}

namespace {

/// The terrain, and the water on it as a second mesh, as glTF.
void write_gltf(const Tin& tin, const ExportMesh& mesh, const GltfTextures& textures,
                ExportFormat format, const MeshExportOptions& mesh_options, const ExportOptions& o,
                const fs::path& out, ExportReport& report) {
    std::optional<ExportMesh> water;
    if (o.water && holds_water(tin.vertices(), kWaterMeshMinDepth)) {
        water = build_water_mesh(tin, mesh_options);
        report.water_vertices = water->positions.size();
        report.water_triangles = water->triangles.size();
    }
    write(out, encode_gltf(mesh, textures, format == ExportFormat::Glb, water ? &*water : nullptr),
          report);
}

/// A height, water-depth, normal or albedo map of the terrain.
void export_map(const Tin& tin, const fs::path& out, ExportFormat format, const ExportOptions& o,
                ExportReport& report, const ProgressCallback& progress) {
    const Rect d = tin.domain();
    const bool water = format == ExportFormat::WaterPng || format == ExportFormat::WaterExr;
    // Metres per sample: the surface's heights, or the water's depths. Both sample the
    // corners, as an import grid does.
    const bool metres_map =
        water || format == ExportFormat::HeightPng || format == ExportFormat::HeightExr;
    const MapGrid grid = metres_map ? corner_grid(d, o) : texture_grid(d, o);
    report.map_width = grid.width;
    report.map_height = grid.height;
    report.map_spacing = grid.spacing();
    // Baking samples the terrain at every texel: most of a map's time; encoding compresses.
    if (progress) progress({0.0, "baking the map"});
    const auto encoding = [&] {
        if (progress) progress({0.6, "encoding and writing the map"});
    };
    if (metres_map) {
        const MapImage metres =
            water ? bake_water_depth_map(tin, grid) : bake_height_map(tin, grid);
        encoding();
        // Both spacings: rounding a side to whole cells spaces the rows differently from
        // the columns (1 x 0.5 m at 0.3 m cells: 0.333 m and 0.25 m), and a re-import with
        // one spacing would stretch the terrain.
        const double cell = report.map_spacing.x;
        const double cell_height = report.map_spacing.y;
        if (format == ExportFormat::HeightPng) {
            report.height_step = height_png_range(metres) / 65535.0;
            write(out, encode_height_png(metres, cell, cell_height, o.georeference), report);
        } else if (format == ExportFormat::WaterPng) {
            report.height_step = water_depth_png_range(metres) / 65535.0;
            write(out, encode_water_depth_png(metres, cell, cell_height, o.georeference), report);
        } else {
            write(out, encode_height_exr(metres, cell, cell_height, o.georeference), report);
        }
    } else if (format == ExportFormat::NormalPng) {
        const MapImage normals = bake_normal_map(tin, grid, o.normal_mode);
        encoding();
        write(out, encode_normal_png(normals, {report.map_spacing, o.georeference}), report);
    } else {
        const MapImage colours = bake_albedo_map(tin, grid, o.palette);
        encoding();
        write(out, encode_albedo_png(colours, {report.map_spacing, o.georeference}), report);
    }
}

/// The mesh's bounds into the report. Every mesh format stores 32-bit floats: a coordinate
/// beyond their range would be written as infinity, so that is an error naming the coordinate.
void measure_bounds(const ExportMesh& mesh, ExportReport& report) {
    report.min = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
    report.max = report.min * -1.0;
    for (const Vec3& p : mesh.positions) {
        report.min = {std::min(report.min.x, p.x), std::min(report.min.y, p.y),
                      std::min(report.min.z, p.z)};
        report.max = {std::max(report.max.x, p.x), std::max(report.max.y, p.y),
                      std::max(report.max.z, p.z)};
    }

    for (const double c :
         {report.min.x, report.min.y, report.min.z, report.max.x, report.max.y, report.max.z}) {
        if (!(std::abs(c) <= static_cast<double>(std::numeric_limits<float>::max()))) {
            std::ostringstream what;
            what << "export: the mesh reaches a coordinate of " << c
                 << " (in the output's units), beyond the 32-bit floats mesh files store; check "
                    "the terrain's heights and --base";
            throw std::invalid_argument(what.str());
        }
    }
}

/// The OBJ, its MTL and its textures, written as one save: a failure leaves none.
void write_obj(const ExportMesh& mesh, const GltfTextures& textures, bool with_textures,
               const fs::path& out, const ExportOptions& o, ExportReport& report) {
    const fs::path dir = out.parent_path();
    // The companions' names go into the OBJ and MTL as bare words (mtllib, map_Kd),
    // which readers split at white space: "my scene.mtl" would read as two names.
    std::string stem = out.stem().string();
    std::replace_if(
        stem.begin(), stem.end(), [](unsigned char c) { return std::isspace(c) != 0; }, '_');
    const std::string mtl = stem + ".mtl";
    ObjMaterial material;
    material.colour = o.palette.colours.front();
    if (with_textures) {
        material.albedo_texture = stem + "_albedo.png";
        material.normal_texture = stem + "_normal.png";
    }
    // The mesh, its material and its textures as one save: a failure leaves none.
    const std::string obj_text = encode_obj(mesh, mtl);
    const std::string mtl_text = encode_mtl(material);
    const auto bytes = [](const std::string& t) {
        return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(t.data()),
                                             t.size());
    };
    std::vector<FileToWrite> files{{out, bytes(obj_text)}, {dir / mtl, bytes(mtl_text)}};
    if (with_textures) {
        files.push_back({dir / material.albedo_texture, textures.albedo_png});
        files.push_back({dir / material.normal_texture, textures.normal_png});
    }
    write_files_atomically(files);
    for (const FileToWrite& f : files)
        report.files.push_back(f.path);
}

}  // namespace

ExportReport export_terrain(const Tin& tin, const fs::path& out, ExportFormat format,
                            const ExportOptions& o, const ProgressCallback& progress) {
    const auto start = std::chrono::steady_clock::now();
    ExportReport report;
    report.format = format;
    const Rect d = tin.domain();
    if (o.palette.colours.empty())
        throw std::invalid_argument("export: the palette has no colours");
    const auto finish = [&] {
        if (progress) progress({1.0, "done"});
        report.ms = elapsed_ms(start);
        return report;
    };

    if (!is_mesh(format)) {
        if (o.max_error || o.base != BaseKind::None || o.up) {
            throw std::invalid_argument(
                "export: --max-error, --base, --skirt and --up apply to "
                "meshes, not maps");
        }
        export_map(tin, out, format, o, report, progress);
        return finish();
    }
    const bool gltf = format == ExportFormat::Gltf || format == ExportFormat::Glb;
    const UpAxis up = o.up.value_or(format == ExportFormat::Obj || gltf ? UpAxis::Y : UpAxis::Z);
    if (gltf && up != UpAxis::Y) {
        throw std::invalid_argument("export: glTF is Y-up by specification; drop --up z");
    }
    MeshExportOptions mesh_options;
    mesh_options.up = up;
    mesh_options.unit_scale = unit_scale_of(o.units);
    mesh_options.base = o.base;
    mesh_options.base_depth = o.base_depth;

    // Shares of the job: simplification (a greedy import of the baked heights) and the two
    // texture bakes are the long stages when they run; the mesh, encoding and writing share
    // the rest.
    const bool with_textures = o.textures && (format == ExportFormat::Obj || gltf);
    const double simplified_at = o.max_error ? 0.4 : 0.0;
    const double mesh_at = simplified_at + 0.1 * (1.0 - simplified_at);
    const double textures_at = with_textures ? mesh_at + 0.6 * (1.0 - mesh_at) : mesh_at;
    std::optional<GreedyResult> simplified;
    if (o.max_error) {
        simplified = simplify(tin, corner_grid(d, o), *o.max_error,
                              progress_part(progress, 0.0, simplified_at));
        report.simplified = simplified->stats;
    }
    if (progress) progress({simplified_at, "building the mesh"});
    ExportMesh mesh = build_export_mesh(simplified ? simplified->tin : tin, mesh_options);
    mesh.georeference = o.georeference;
    report.vertices = mesh.positions.size();
    report.triangles = mesh.triangles.size();
    measure_bounds(mesh, report);

    // Textures come from the original terrain: simplification changes geometry, not looks.
    GltfTextures textures;
    textures.base_colour = o.palette.colours.front();
    if (with_textures) {
        if (progress) progress({mesh_at, "baking the albedo texture"});
        const MapGrid grid = texture_grid(d, o);
        report.map_width = grid.width;
        report.map_height = grid.height;
        report.map_spacing = grid.spacing();
        const TexelFrame frame{report.map_spacing, o.georeference};
        textures.albedo_png = encode_albedo_png(bake_albedo_map(tin, grid, o.palette), frame);
        if (progress) progress({(mesh_at + textures_at) / 2.0, "baking the normal texture"});
        // In the mesh's own tangent frame, as glTF's normalTexture (and OBJ importers reading
        // map_Bump) expect: the terrain's normals relative to the exported mesh's.
        textures.normal_png = encode_normal_png(
            bake_tangent_normal_map(simplified ? simplified->tin : tin,
                                    bake_normal_map(tin, grid, o.normal_mode), grid),
            frame);
    }

    if (progress) progress({textures_at, "encoding and writing the mesh"});
    switch (format) {
        case ExportFormat::Obj:
            write_obj(mesh, textures, with_textures, out, o, report);
            break;
        case ExportFormat::Ply:
            write(out, encode_ply(mesh), report);
            break;
        case ExportFormat::Stl:
            write(out, encode_stl(mesh), report);
            break;
        case ExportFormat::Gltf:
        case ExportFormat::Glb:
            write_gltf(tin, mesh, textures, format, mesh_options, o, out, report);
            break;
        default:
            break;
    }
    return finish();
}

nlohmann::json to_json(const ExportReport& r) {
    nlohmann::json j;
    j["format"] = to_string(r.format);
    std::vector<std::string> files;
    for (const auto& f : r.files)
        files.push_back(f.string());
    j["files"] = files;
    if (r.vertices > 0) {
        j["vertices"] = r.vertices;
        j["triangles"] = r.triangles;
        j["bbox"] = {{"min", {r.min.x, r.min.y, r.min.z}}, {"max", {r.max.x, r.max.y, r.max.z}}};
    }
    if (r.map_width > 0) {
        j["map"] = {{"width", r.map_width},
                    {"height", r.map_height},
                    {"cell_size", r.map_spacing.x},
                    {"cell_height", r.map_spacing.y}};
    }
    if (r.height_step > 0.0) j["height_step"] = r.height_step;
    if (r.water_triangles > 0)
        j["water"] = {{"vertices", r.water_vertices}, {"triangles", r.water_triangles}};
    if (r.simplified) {
        j["simplified"] = {{"points", r.simplified->points},
                           {"triangles", r.simplified->triangles},
                           {"max_error", r.simplified->max_error},
                           {"rmsd", r.simplified->rmsd}};
    }
    j["ms"] = r.ms;
    return j;
}

}  // namespace sandtin
