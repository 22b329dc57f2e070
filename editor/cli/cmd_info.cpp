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

namespace sandtin::cli {

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
        std::cout << "  valid             yes\n";
    }
    return 0;
}

}  // namespace sandtin::cli
