// sandtin info: load a session and describe its terrain.

#include <iostream>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "terrain_report.hpp"

namespace sandtin::cli {

int run_info(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--json", 0}});
    args.require_positionals(1, "sandtin info scene.sandtin [--json]");
    const std::string path = args.positionals()[0];
    const Session session = load_session(path);
    TinOptions options;
    options.track_changes = false;
    const Tin tin = session_terrain(session, path, options);
    // Valid: from_snapshot ends with check_valid() and refuses the file on any problem (a
    // second check cost a quarter of `info` on a 10^6-vertex scene).
    nlohmann::json j = describe_terrain(tin, false);
    j["valid"] = true;
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
        std::cout << "  valid             yes\n";
    }
    return 0;
}

}  // namespace sandtin::cli
