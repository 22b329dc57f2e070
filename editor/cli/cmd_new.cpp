// sandtin new: create a terrain and save it as a session.

#include <cmath>
#include <iostream>

#include "arguments.hpp"
#include "commands.hpp"
#include "io/session_file.hpp"
#include "session_output.hpp"
#include "terrain_report.hpp"
#include "tin/flat_bedrock.hpp"
#include "tin/tin.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::cli {

namespace {
constexpr const char* kNewUsage =
    "sandtin new (--flat W H | --grid W H NX NY) [--points N] [--seed S] [--height Z] "
    "[--sand-depth D] "
    "-o scene.sandtin [--json]";
}

int run_new(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--flat", 2},
                               {"--grid", 4},
                               {"--points", 1},
                               {"--seed", 1},
                               {"--height", 1},
                               {"--sand-depth", 1},
                               {"-o", 1},
                               {"--json", 0}});
    args.require_positionals(0, kNewUsage);
    if (args.has("--flat") == args.has("--grid")) {
        throw UsageError("give exactly one of --flat W H or --grid W H NX NY\nusage: " +
                         std::string(kNewUsage));
    }
    const std::string out = args.text("-o");
    check_session_output(out);  // before the work, not after it
    const double z = args.number_or("--height", 0.0);
    if (!(std::abs(z) <= kMaxHeight))
        throw UsageError("--height must lie within -1e9 and 1e9 m\nusage: " +
                         std::string(kNewUsage));
    std::optional<double> sand_depth;
    if (args.has("--sand-depth")) {
        sand_depth = args.number("--sand-depth");
        if (!(*sand_depth >= 0.0 && *sand_depth <= kMaxHeight)) {
            throw UsageError("--sand-depth must lie within 0 and 1e9 m\nusage: " +
                             std::string(kNewUsage));
        }
    }
    const auto constant = [z](Vec2) { return z; };
    TinOptions options;
    options.track_changes = false;

    auto size_of = [&](const std::string& opt) {
        const double w = args.number(opt, 0);
        const double h = args.number(opt, 1);
        if (!(w > 0.0 && h > 0.0)) throw UsageError(opt + ": width and height must be positive");
        return Rect::from_size(w, h);
    };
    Tin tin = [&] {
        // The seed places random points: without them it would be ignored.
        if (args.has("--seed") && args.count_or("--points", 0) == 0)
            throw UsageError("--seed applies to --flat with --points N");
        if (args.has("--grid")) {
            if (args.has("--points")) throw UsageError("--points applies to --flat, not --grid");
            const auto nx = args.count("--grid", 2);
            const auto ny = args.count("--grid", 3);
            if (nx < 1 || ny < 1 || nx > 20000 || ny > 20000) {
                throw UsageError("--grid: NX and NY must lie in 1..20000");
            }
            return Tin::regular_grid(size_of("--grid"), static_cast<int>(nx), static_cast<int>(ny),
                                     constant, options);
        }
        const auto n = args.count_or("--points", 0);
        if (n > 50'000'000) throw UsageError("--points: at most 50 000 000 points");
        const Rect domain = size_of("--flat");
        if (n == 0) return Tin::flat_rectangle(domain, z, options);
        return Tin::random_points(domain, n, args.count_or("--seed", 1), constant, options);
    }();

    if (sand_depth) lay_flat_bedrock(tin, z - *sand_depth);
    Session session;
    session.terrain = tin.snapshot();
    save_session(out, session);
    if (args.has("--json")) {
        nlohmann::json j = describe_terrain(tin, false);
        j["file"] = out;
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "wrote " << out << ": " << tin.vertex_count() << " vertices, "
                  << tin.triangle_count() << " triangles\n";
    }
    return 0;
}

}  // namespace sandtin::cli
