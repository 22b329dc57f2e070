// sandtin demo: the default batch job. Builds the default sandbox, drags a ring-shaped tool
// rim along a curve (constrained edges, as a stroke enforces them), and prints the statistics.

#include <cmath>
#include <iostream>
#include <numbers>

#include "arguments.hpp"
#include "commands.hpp"
#include "terrain_report.hpp"

namespace sandtin::cli {

int run_demo(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--json", 0}});
    args.require_positionals(0, "sandtin demo [--json]");
    const Rect domain = Rect::from_size(4.0, 4.0);
    auto dunes = [](Vec2 p) {
        return 0.12 * std::sin(1.7 * p.x + 0.4 * p.y) + 0.05 * std::sin(3.1 * p.y - 0.8 * p.x);
    };
    Tin tin = Tin::random_points(domain, 20000, 2026, dunes);
    const double volume_before = tin.volume();

    LocateHint hint;
    Generation generation = 1;
    std::size_t stamps = 0;
    for (double t = 0.0; t <= 1.0; t += 0.02, ++stamps) {
        const Vec2 centre{0.8 + 2.4 * t, 2.0 + 0.8 * std::sin(2.0 * std::numbers::pi * t)};
        std::vector<VertexId> rim;
        for (int i = 0; i < 12; ++i) {
            const double a = 2.0 * std::numbers::pi * i / 12.0;
            rim.push_back(
                tin.insert_point_on_surface(centre + Vec2{std::cos(a), std::sin(a)} * 0.15, &hint));
        }
        // Older rims under the new footprint are released, as a tool stroke does.
        std::vector<Vec2> footprint;
        for (VertexId v : rim)
            footprint.push_back(tin.position(v));
        ReleaseFilter older;
        older.older_than = generation;
        older.touching_polygon = footprint;
        tin.release_constraints(older);
        tin.insert_constraint(rim, true, generation++);
        tin.take_changes();
    }
    nlohmann::json j = describe_terrain(tin);
    j["stamps"] = stamps;
    j["volume_before"] = volume_before;
    if (args.has("--json")) {
        std::cout << j.dump(2) << "\n";
    } else {
        std::cout << "sandtin demo: default sandbox 4 x 4 m, " << stamps
                  << " stamps along a curve\n"
                  << j.dump(2) << "\n";
    }
    return j["valid"].get<bool>() ? 0 : 1;
}

}  // namespace sandtin::cli
