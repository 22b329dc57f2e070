#include "io/script_weather.hpp"

#include <vector>

namespace sandtin {

WeatherOp parse_weather_op(JsonFields& f) {
    WeatherOp op;
    op.iterations = static_cast<int>(f.integer("iterations", 1, 1, 1'000'000));
    op.settings.strength = f.in_range("strength", op.settings.strength, 0.0, 1.0);
    op.settings.power = f.in_range("power", op.settings.power, 1.0, 100.0);
    if (const auto disc = f.disc("to weather a disc")) {
        op.centre = disc->centre;
        op.radius = disc->radius;
    }
    f.reject_unknown();
    return op;
}

nlohmann::json run_weather_op(const WeatherOp& op, Tin& tin) {
    const double ledger0 = tin.volume_ledger();
    WeatheringReport total;
    int run = 0;
    if (op.centre) {
        // The disc's vertices are found once: weathering moves no vertex in the plane and
        // inserts none, so the set stays the same over the iterations.
        const std::vector<VertexId> disc = tin.vertices_in_disc(*op.centre, op.radius);
        for (; run < op.iterations; ++run) {
            const WeatheringReport r = weather_vertices(tin, disc, {}, op.settings);
            total += r;
            if (r.vertices_worn == 0) break;
        }
    } else {
        for (; run < op.iterations; ++run) {
            const WeatheringReport r = weather_terrain(tin, 1, op.settings);
            total += r;
            if (r.vertices_worn == 0) break;
        }
    }
    return {{"iterations", run},
            {"vertices_worn", total.vertices_worn},
            {"volume_moved_m3", total.volume_moved},
            {"deepest_wear_m", total.deepest_wear},
            {"largest_curvature", total.largest_curvature},
            {"volume_change", tin.volume_ledger() - ledger0}};
}

}  // namespace sandtin
