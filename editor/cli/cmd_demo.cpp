// sandtin demo: the default batch job. Loads the default scene (assets/scenes/default.sandtin),
// runs a short scripted session on it -- a λ stroke with relaxation between stamps, a pour, and
// erosion until the sand rests -- and prints the statistics of every step and of the result.

#include <iostream>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "terrain_report.hpp"
#include "tools/sculpt_context.hpp"
#include "util/asset_path.hpp"

namespace sandtin::cli {

namespace {

/// The demo session, in the coordinates of the default scene's domain (fractions of it).
nlohmann::json demo_script(const Rect& d) {
    auto at = [&](double fx, double fy) {
        return nlohmann::json::array({d.min.x + fx * d.width(), d.min.y + fy * d.height()});
    };
    const double size = std::min(d.width(), d.height());
    return {{"version", 1},
            {"settings", {{"relocation_radius", 0.02 * size}}},
            {"operations",
             {{{"op", "stroke"},
               {"tool", {{"asset", "lambda"}, {"scale", 0.012 * size}}},  // a 12 cm λ on 1 m
               {"path", {at(0.2, 0.5), at(0.4, 0.62), at(0.6, 0.4), at(0.8, 0.5)}},
               {"curve", true},
               {"spacing", 0.01 * size},
               {"depth", 0.008 * size},
               {"erode", true},
               {"erode_iterations", 2}},
              {{"op", "pour"},
               {"at", at(0.5, 0.3)},
               {"volume", 2e-5 * size * size * size},
               {"radius", 0.03 * size}},
              {{"op", "erode"}, {"until_rest", true}, {"max_iterations", 2000}}}}};
}

}  // namespace

int run_demo(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--json", 0}});
    args.require_positionals(0, "sandtin demo [--json]");
    const std::filesystem::path scene = find_asset("scenes/default.sandtin");
    Session session = load_session(scene);
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::from_snapshot(session.terrain, options);
    const double volume_before = tin.volume();

    const nlohmann::json script_json = demo_script(tin.domain());
    const Script script = parse_script(script_json.dump(), "demo", scene.parent_path());
    SculptContext context(tin.domain());
    context.set_next_generation(session.next_generation);
    nlohmann::json steps = run_script(script, tin, context);

    double reported = 0.0;
    std::size_t stamps = 0;
    for (const nlohmann::json& s : steps) {
        reported += s.value("volume_change", 0.0);
        stamps += s.value("stamps_applied", std::size_t{0});
    }
    nlohmann::json j = describe_terrain(tin);
    j["scene"] = scene.string();
    j["stamps"] = stamps;
    j["volume_before"] = volume_before;
    j["volume_reported"] = reported;
    j["steps"] = std::move(steps);
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "sandtin demo: " << scene.filename().string() << ", a λ stroke of " << stamps
                  << " stamps with erosion, a pour, erosion to rest\n"
                  << j.dump(2) << "\n";
    }
    return j["valid"].get<bool>() ? 0 : 1;
}

}  // namespace sandtin::cli
