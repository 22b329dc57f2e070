// sandtin export: a session to a mesh (OBJ, PLY, STL, glTF, GLB) or a map (height PNG/EXR,
// normal or albedo PNG).

#include <iostream>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/export_terrain.hpp"
#include "io/import_grid.hpp"
#include "io/scene_materials.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "progress_line.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::cli {

namespace {

constexpr const char* kExportUsage =
    "sandtin export scene.sandtin -o out.(obj|ply|stl|gltf|glb|png|exr) "
    "[--map height|normal|albedo|water] [--up y|z] [--units m|cm|mm|km|in|ft] "
    "[--base DEPTH | --skirt DEPTH] [--max-error E] [--cell-size m] [--size N] "
    "[--no-textures] [--no-water] [--faceted] [--json]";

}  // namespace

int run_export(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"-o", 1},
                               {"--map", 1},
                               {"--up", 1},
                               {"--units", 1},
                               {"--base", 1},
                               {"--skirt", 1},
                               {"--max-error", 1},
                               {"--cell-size", 1},
                               {"--size", 1},
                               {"--no-textures", 0},
                               {"--no-water", 0},
                               {"--faceted", 0},
                               {"--json", 0}});
    args.require_positionals(1, kExportUsage);
    const std::string out = args.text("-o");
    check_writable(out);  // before the work, not after it
    ExportFormat format{};
    ExportOptions options;
    try {
        format = export_format_for(out, args.text_or("--map", ""));
        options.units = args.text_or("--units", "m");
        (void)unit_scale_of(options.units);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    if (args.has("--up")) {
        const std::string up = args.text("--up");
        if (up != "y" && up != "z") throw UsageError("--up: '" + up + "' is not y or z");
        options.up = up == "y" ? UpAxis::Y : UpAxis::Z;
    }
    if (args.has("--base") && args.has("--skirt")) {
        throw UsageError("give at most one of --base and --skirt");
    }
    for (const char* opt : {"--base", "--skirt"}) {
        if (!args.has(opt)) continue;
        options.base = std::string(opt) == "--base" ? BaseKind::Solid : BaseKind::Skirt;
        options.base_depth = args.number(opt);
        if (!(options.base_depth > 0.0)) {
            throw UsageError(std::string(opt) + ": the depth must be a positive number of metres");
        }
    }
    if (args.has("--max-error")) {
        options.max_error = args.number("--max-error");
        if (*options.max_error < 0.0) throw UsageError("--max-error must be >= 0 metres");
    }
    if (args.has("--cell-size")) {
        options.cell_size = args.number("--cell-size");
        if (!(*options.cell_size > 0.0)) throw UsageError("--cell-size must be positive");
        options.texel_size = options.cell_size;  // normal and albedo maps, mesh textures
    }
    if (args.has("--size")) {
        const auto n = args.count("--size");
        if (n < 2 || n > 16384) throw UsageError("--size must lie in 2..16384");
        options.map_size = static_cast<std::uint32_t>(n);
    }
    options.textures = !args.has("--no-textures");
    options.water = !args.has("--no-water");
    if (args.has("--faceted")) options.normal_mode = NormalMode::Faceted;
    // An option the chosen output would ignore is an error: the user expected it to act.
    const bool textured_mesh =
        format == ExportFormat::Obj || format == ExportFormat::Gltf || format == ExportFormat::Glb;
    const bool mesh = textured_mesh || format == ExportFormat::Ply || format == ExportFormat::Stl;
    const bool samples_a_grid = !mesh || (textured_mesh && options.textures) || options.max_error;
    const auto refuse = [&](const char* option, const char* applies_to) {
        if (args.has(option)) {
            throw UsageError(std::string(option) + " applies to " + applies_to + ", not to '" +
                             out + "'\nusage: " + kExportUsage);
        }
    };
    if (args.has("--cell-size") && args.has("--size"))
        throw UsageError("give at most one of --cell-size and --size");
    if (!samples_a_grid) {
        refuse("--cell-size", "maps, textured meshes and --max-error");
        refuse("--size", "maps, textured meshes and --max-error");
    }
    if (!mesh) refuse("--units", "meshes");
    if (!textured_mesh) refuse("--no-textures", ".obj, .gltf and .glb");
    if (format != ExportFormat::Gltf && format != ExportFormat::Glb)
        refuse("--no-water", ".gltf and .glb (the water surface as a second mesh)");
    if (!(format == ExportFormat::NormalPng || (textured_mesh && options.textures)))
        refuse("--faceted", "normal maps, and the textures of .obj, .gltf and .glb");

    Session session = load_session(args.positionals()[0]);
    TinOptions tin_options;
    tin_options.track_changes = false;
    const Tin tin = take_session_terrain(session, args.positionals()[0], tin_options);
    // Maps and simplification sample the grid the terrain was imported on while it still lies
    // on it, so that export followed by import gives the same samples; a finer one once edits
    // put vertices between those samples.
    const std::optional<DefaultSampling> sampling =
        apply_import_defaults(tin, session.metadata_json, options, args.has("--size"));
    // The colours the scene was sculpted with, recoloured materials included.
    options.palette = export_palette(materials_or_presets(session.metadata_json));
    ExportReport report;
    ProgressLine progress("export " + std::filesystem::path(out).filename().string());
    try {
        report = export_terrain(tin, out, format, options, progress.callback());
        progress.finish();
    } catch (const std::invalid_argument& e) {
        // An option the user gave is a usage error (exit 2); a default the session file supplied
        // is bad data in that file (exit 1).
        if (sampling) {
            throw std::runtime_error(args.positionals()[0] +
                                     ": the import cell size in the session's metadata cannot be "
                                     "used (" +
                                     std::string(e.what()) + "); give --cell-size or --size");
        }
        throw UsageError(e.what());
    }
    const bool sampled = report.map_width > 0 && report.vertices == 0;  // a map
    const bool uses_sampling = sampling && (sampled || options.max_error);
    if (args.has("--json")) {
        nlohmann::json j = to_json(report);
        if (uses_sampling) {
            j["default_sampling"] = {
                {"cell_size", sampling->cell_size},
                {"cell_height",
                 sampling->cell_height > 0.0 ? sampling->cell_height : sampling->cell_size},
                {"grid", sampling->edited ? "finer than the import grid, which edits have left"
                                          : "the import grid"}};
        }
        std::cout << j.dump(2) << "\n";
    } else {
        if (uses_sampling && sampling->edited) {
            std::cout << "note: edits put vertices between the samples of the grid this terrain "
                         "was imported on; sampling every "
                      << sampling->cell_size << " m instead, so that they are kept "
                      << "(--cell-size or --size choose)\n";
        }
        std::cout << "exported " << args.positionals()[0] << " as " << to_string(report.format);
        if (report.vertices > 0) {
            std::cout << ": " << report.vertices << " vertices, " << report.triangles
                      << " triangles";
        }
        if (report.map_width > 0) {
            std::cout << (report.vertices > 0 ? ", maps " : ": ") << report.map_width << " x "
                      << report.map_height;
        }
        std::cout << "\n";
        for (const auto& f : report.files)
            std::cout << "wrote " << f.string() << "\n";
    }
    return 0;
}

}  // namespace sandtin::cli
