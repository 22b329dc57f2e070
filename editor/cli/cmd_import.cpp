// sandtin import: a heightmap (PNG, Terrain-RGB, ESRI ASCII grid, GeoTIFF, EXR) to an
// error-bounded TIN, saved as a session.

#include <cmath>
#include <iostream>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/heightmap_import.hpp"
#include "io/session_file.hpp"
#include "progress_line.hpp"
#include "session_output.hpp"
#include "tin/tin.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::cli {

namespace {

constexpr const char* kImportUsage =
    "sandtin import FILE --max-error E [--max-points N] [--pixel-size m] [--z-scale s] "
    "[--z-offset m] [--encoding auto|gray|terrain-rgb] [--nonfinite-as-nodata] "
    "[--max-size W H] -o scene.sandtin [--json]";

PngHeightEncoding encoding_of(const std::string& text) {
    if (text == "auto") return PngHeightEncoding::Auto;
    if (text == "gray" || text == "grey") return PngHeightEncoding::Gray;
    if (text == "terrain-rgb") return PngHeightEncoding::TerrainRgb;
    throw UsageError("--encoding: '" + text + "' is not one of auto, gray, terrain-rgb");
}

}  // namespace

int run_import(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--max-error", 1},
                               {"--max-points", 1},
                               {"--pixel-size", 1},
                               {"--z-scale", 1},
                               {"--z-offset", 1},
                               {"--encoding", 1},
                               {"--nonfinite-as-nodata", 0},
                               {"--max-size", 2},
                               {"-o", 1},
                               {"--json", 0}});
    args.require_positionals(1, kImportUsage);
    if (!args.has("--max-error")) {
        throw UsageError("missing required option '--max-error'\nusage: " +
                         std::string(kImportUsage));
    }
    const std::string out = args.text("-o");
    check_session_output(out);  // before the work, not after it
    check_not_overwriting(out, args.positionals()[0], "the heightmap being imported");
    ImportOptions options;
    options.greedy.max_error = args.number("--max-error");
    if (options.greedy.max_error < 0.0) throw UsageError("--max-error must be >= 0 metres");
    options.greedy.max_points = args.count_or("--max-points", 0);
    if (options.greedy.max_points != 0 && options.greedy.max_points < 4) {
        throw UsageError("--max-points must be at least 4 (the domain corners)");
    }
    if (args.has("--pixel-size")) {
        options.read.pixel_size = args.number("--pixel-size");
        if (!(*options.read.pixel_size > 0.0)) throw UsageError("--pixel-size must be positive");
    }
    if (args.has("--z-scale")) options.read.z_scale = args.number("--z-scale");
    if (args.has("--z-offset")) {
        options.read.z_offset = args.number("--z-offset");
        if (!(std::abs(*options.read.z_offset) <= kMaxHeight))
            throw UsageError("--z-offset must lie within -1e9 and 1e9 m");
    }
    options.read.png_encoding = encoding_of(args.text_or("--encoding", "auto"));
    options.read.nonfinite_as_nodata = args.has("--nonfinite-as-nodata");
    if (args.has("--max-size")) {
        const auto w = args.count("--max-size", 0);
        const auto h = args.count("--max-size", 1);
        if (w < 2 || h < 2 || w > 1'000'000 || h > 1'000'000) {
            throw UsageError("--max-size: W and H must lie in 2..1000000");
        }
        options.read.limits.max_width = static_cast<std::uint32_t>(w);
        options.read.limits.max_height = static_cast<std::uint32_t>(h);
    }

    ProgressLine progress("import " +
                          std::filesystem::path(args.positionals()[0]).filename().string());
    const ImportResult result =
        import_heightmap(args.positionals()[0], options, progress.callback());
    progress.finish();
    if (result.report.source_bands > 1) {
        std::cerr << "sandtin import: warning: " << args.positionals()[0] << " has "
                  << result.report.source_bands
                  << " bands; the heights are read from the first (is it imagery rather than "
                     "an elevation model?)\n";
    }
    Session session;
    session.terrain = result.tin.snapshot();
    nlohmann::json report = to_json(result.report);
    session.metadata_json = nlohmann::json{{"import", report}}.dump();
    save_session(out, session);

    if (args.has("--json")) {
        report["file"] = out;
        std::cout << report.dump(2) << "\n";
    } else {
        const ImportReport& r = result.report;
        std::cout << "imported " << r.source << " (" << r.format << ", " << r.width << " x "
                  << r.height << " samples, " << r.cell_size << " m)\n"
                  << "  points      " << r.stats.points << "\n"
                  << "  triangles   " << r.stats.triangles << "\n"
                  << "  max error   " << r.stats.max_error << " m (target " << r.greedy.max_error
                  << " m" << (r.stats.reached_error ? ")" : ", NOT reached: point limit)") << "\n"
                  << "  rmsd        " << r.stats.rmsd << " m\n"
                  << "  no-data     " << r.nodata_samples << " samples (filled, not measured)\n"
                  << "  time        " << r.total_ms << " ms\n"
                  << "wrote " << out << "\n";
    }
    return 0;
}

}  // namespace sandtin::cli
