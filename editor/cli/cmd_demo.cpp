// sandtin demo: the default batch job. Loads the default scene (assets/scenes/default.sandtin),
// runs a short scripted session on it -- a λ stroke with relaxation between stamps, a pour, and
// erosion until the sand rests -- saves the result as a session, and prints a short summary
// with the command that opens it in the editor (--json: the statistics of every step).

#include <iomanip>
#include <iostream>
#include <utility>

#include "arguments.hpp"
#include "commands.hpp"
#include "editor_command.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "progress_line.hpp"
#include "session_output.hpp"
#include "terrain_report.hpp"
#include "tools/sculpt_context.hpp"
#include "util/asset_path.hpp"

namespace sandtin::cli {

namespace {

constexpr const char* kDemoUsage = "sandtin demo [-o out.sandtin] [--json]";
/// Where the result goes without -o: the current directory, under a name that says what it is.
constexpr const char* kDefaultOutput = "sandtin-demo.sandtin";

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

/// The demo in a few lines: what it did, the terrain's numbers, where it went and how to look.
void print_summary(const std::filesystem::path& scene, const std::filesystem::path& out,
                   const Tin& tin, const nlohmann::json& j) {
    const nlohmann::json& steps = j["steps"];
    const nlohmann::json& erode = steps.at(2);
    const Rect d = tin.domain();
    const double zmin = j["bbox"]["min"][2].get<double>();
    const double zmax = j["bbox"]["max"][2].get<double>();
    std::cout << std::setprecision(4);
    std::cout << "sandtin demo: the default scene (" << scene.filename().string() << ", "
              << d.width() << " x " << d.height() << " m) after a λ stroke of " << j["stamps"]
              << " stamps\n  with erosion after each, a pour of "
              << steps.at(1)["volume"].get<double>() << " m³ and erosion ";
    if (erode.value("at_rest", false)) {
        std::cout << "until the sand rested (" << erode["iterations"] << " iterations)\n";
    } else {
        std::cout << "for " << erode["iterations"] << " iterations (not yet at rest)\n";
    }
    std::cout << "  vertices           " << j["vertices"] << "\n"
              << "  triangles          " << j["triangles"] << "\n"
              << "  constrained edges  " << j["constrained_edges"] << "\n"
              << "  volume             " << j["volume"].get<double>() << " m³ (was "
              << j["volume_before"].get<double>() << " m³)\n"
              << "  relief             " << zmax - zmin << " m (heights " << zmin << " to " << zmax
              << " m)\n"
              << "  valid              " << (j["valid"].get<bool>() ? "yes" : "NO") << "\n"
              << "wrote " << path_for_display(out).string() << "\n"
              << "open it in the editor:\n"
              << "  " << editor_command(out) << "\n"
              << "(sandtin demo --json prints the statistics of every step)\n";
}

}  // namespace

int run_demo(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--json", 0}, {"-o", 1}});
    args.require_positionals(0, kDemoUsage);
    const std::string out = args.text_or("-o", kDefaultOutput);
    check_session_output(out);  // before the work, not after it
    const std::filesystem::path scene = find_asset("scenes/default.sandtin");
    Session session = load_session(scene);
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::from_snapshot(std::move(session.terrain), options);
    const double volume_before = tin.volume();

    const nlohmann::json script_json = demo_script(tin.domain());
    const Script script = parse_script(script_json.dump(), "demo", scene.parent_path());
    SculptContext context(tin.domain());
    context.set_next_generation(session.next_generation);
    ProgressLine progress("demo");
    nlohmann::json steps = run_script(script, tin, context, {}, nullptr, progress.callback());
    progress.finish();

    // The result as a session the editor opens, with the scene's metadata (its materials).
    session.terrain = tin.snapshot();
    session.next_generation = context.peek_generation();
    save_session(out, session);

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
    j["file"] = out;
    j["editor_command"] = editor_command(out);
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        print_summary(scene, out, tin, j);
    }
    return j["valid"].get<bool>() ? 0 : 1;
}

}  // namespace sandtin::cli
