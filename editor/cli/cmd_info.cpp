// sandtin info: load a session and describe its terrain.

#include <iomanip>
#include <iostream>
#include <sstream>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/scene_materials.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "terrain_report.hpp"
#include "water/water_summary.hpp"

namespace sandtin::cli {

namespace {

/// The water standing on the terrain (VertexArrays::water_depth).
nlohmann::json describe_water(const Tin& tin) {
    const WaterSummary w = measure_water(tin);
    return {{"m3", w.volume}, {"wet_vertices", w.wet_vertices}, {"max_depth_m", w.max_depth}};
}

}  // namespace

int run_info(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--json", 0}});
    args.require_positionals(1, "sandtin info scene.sandtin [--json]");
    const std::string path = args.positionals()[0];
    Session session = load_session(path);
    TinOptions options;
    options.track_changes = false;
    const Tin tin = take_session_terrain(session, path, options);
    // Valid: whatever from_snapshot accepts passes check_valid() (its checks refuse the file on
    // any problem; a second check cost a quarter of `info` on a 10^6-vertex scene).
    nlohmann::json j = describe_terrain(tin, false);
    j["valid"] = true;
    j["slopes"] = describe_slopes(tin, materials_or_presets(session.metadata_json));
    j["water"] = describe_water(tin);
    if (session.stale_water_dropped) j["water"]["dropped_stale"] = true;
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << path << "\n"
                  << "  vertices          " << j["vertices"] << "\n"
                  << "  triangles         " << j["triangles"] << "\n"
                  << "  constrained edges " << j["constrained_edges"] << "\n"
                  << "  volume            " << j["volume"] << " m^3 above z = 0\n"
                  << "  bbox              " << j["bbox"].dump() << "\n";
        if (j.contains("sand")) {
            std::cout << "  sand over bedrock " << j["sand"]["min_thickness"] << " to "
                      << j["sand"]["max_thickness"] << " m thick\n";
        }
        const nlohmann::json& s = j["slopes"];
        std::ostringstream slopes;
        slopes << std::setprecision(3) << "  steeper than repose " << s["steep_faces"] << " of "
               << s["faces"] << " faces, " << 100.0 * s["steep_share_of_slopes"].get<double>()
               << " % of the slopes' area";
        if (s["faces"].get<std::size_t>() > 0) {
            slopes << "; steepest " << s["max_ratio"].get<double>() << " x tan(repose) at ("
                   << s["steepest_at"][0].get<double>() << ", " << s["steepest_at"][1].get<double>()
                   << ") m";
        }
        std::cout << slopes.str() << "\n";
        const nlohmann::json& w = j["water"];
        if (w["wet_vertices"].get<std::size_t>() > 0) {
            std::cout << "  water             " << w["m3"] << " m^3 on " << w["wet_vertices"]
                      << " vertices, deepest " << w["max_depth_m"] << " m\n";
        }
        if (session.stale_water_dropped) {
            std::cout << "  water             dropped: the file's water was written for a terrain "
                         "that an older build has since edited\n";
        }
        std::cout << "  valid             yes\n";
    }
    return 0;
}

}  // namespace sandtin::cli
