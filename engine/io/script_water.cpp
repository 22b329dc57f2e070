#include "io/script_water.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tin/vertex_arrays.hpp"
#include "water/sediment_transport.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

namespace {

/// The longest step between two applications of the sources: rain and nozzles arrive in
/// steps no longer than this even when the water is shallow and its CFL step long.
constexpr double kLongestStep = 0.05;  // s

Rain parse_rain(const nlohmann::json& object, const std::string& context) {
    JsonFields r(object, context);
    Rain rain;
    rain.mm_per_hour = r.in_range("mm_per_hour", 0.0, 0.0, 1e4);
    if (r.has("centre") != r.has("radius"))
        r.fail("give both 'centre' and 'radius' for rain on a disc, or neither");
    if (r.has("centre")) {
        rain.centre = r.point("centre");
        rain.radius = r.positive("radius", 0.0);
    }
    r.reject_unknown();
    return rain;
}

Nozzle parse_nozzle(const nlohmann::json& object, const std::string& context) {
    JsonFields n(object, context);
    Nozzle nozzle;
    nozzle.at = n.point("at");
    nozzle.litres_per_second = n.in_range("litres_per_second", 0.0, 0.0, 1e4);
    n.reject_unknown();
    return nozzle;
}

}  // namespace

WaterOp parse_water_op(JsonFields& f) {
    WaterOp op;
    op.seconds = f.in_range("seconds", 0.0, 0.0, 1e6);
    if (!(op.seconds > 0.0)) f.fail_field("seconds", "must be a positive number of seconds");
    if (const nlohmann::json* rain = f.get("rain")) {
        const std::string context = f.context() + ": rain";
        if (rain->is_array()) {
            for (std::size_t k = 0; k < rain->size(); ++k)
                op.sources.rain.push_back(
                    parse_rain((*rain)[k], context + "[" + std::to_string(k) + "]"));
        } else {
            op.sources.rain.push_back(parse_rain(*rain, context));
        }
    }
    if (const nlohmann::json* nozzles = f.get("nozzles")) {
        if (!nozzles->is_array()) f.fail_field("nozzles", "must be an array of nozzles");
        for (std::size_t k = 0; k < nozzles->size(); ++k)
            op.sources.nozzles.push_back(
                parse_nozzle((*nozzles)[k], f.context() + ": nozzles[" + std::to_string(k) + "]"));
    }
    op.sources.evaporation_mm_per_hour = f.in_range("evaporation_mm_per_hour", 0.0, 0.0, 1e4);
    if (const nlohmann::json* sides = f.get("open_sides")) {
        if (!sides->is_array()) f.fail_field("open_sides", "must be an array of side names");
        for (const nlohmann::json& side : *sides) {
            const std::string name = side.is_string() ? side.get<std::string>() : "";
            if (name == "west")
                op.open.west = true;
            else if (name == "east")
                op.open.east = true;
            else if (name == "south")
                op.open.south = true;
            else if (name == "north")
                op.open.north = true;
            else
                f.fail_field("open_sides", "names a side other than west, east, south, north");
        }
    }
    op.friction = f.in_range("friction", op.friction, 0.0, 1e3);
    op.wet_moisture = f.in_range("wet_moisture", op.wet_moisture, 0.0, 1.0);
    op.wet_depth = f.positive("wet_depth", op.wet_depth);
    op.erode = f.boolean("erode", false);
    if (op.sources.rain.empty() && op.sources.nozzles.empty())
        f.fail("give 'rain' or 'nozzles': water needs a source");
    f.reject_unknown();
    return op;
}

nlohmann::json run_water_op(const WaterOp& op, Tin& tin) {
    VirtualPipeOptions options;
    options.friction = op.friction;
    VirtualPipes water(water_mesh_of(tin), options);
    open_borders(water, tin.domain(), op.open);
    std::optional<SedimentTransport> sediment;
    if (op.erode) {
        std::vector<double> rock = tin.vertices().bedrock;
        for (double& z : rock) {
            if (!(z > 0.5 * kNoBedrock)) z = -std::numeric_limits<double>::infinity();
        }
        sediment.emplace(water.mesh(), std::move(rock));
    }
    std::vector<double> deepest(water.vertex_count(), 0.0);
    SourceReport sources;
    double t = 0.0;
    std::size_t steps = 0;
    while (t < op.seconds) {
        const double dt = std::min({water.stable_time_step(), kLongestStep, op.seconds - t});
        const SourceReport r = apply_sources(water, op.sources, dt);
        sources.added += r.added;
        sources.evaporated += r.evaporated;
        water.step(dt);
        if (sediment) sediment->step(water, dt);
        for (std::size_t v = 0; v < deepest.size(); ++v)
            deepest[v] = std::max(deepest[v], water.depth(v));
        t += dt;
        ++steps;
    }
    // The sand the water moved, into the terrain (journaled, so the GPU mirror and undo see
    // it): what is still suspended settles where it is.
    double sand_moved = 0.0, volume_change = 0.0;
    if (sediment) {
        sediment->settle_all(water);
        std::vector<VertexId> moved;
        std::vector<double> heights;
        const VertexArrays& va = tin.vertices();
        for (std::size_t v = 0; v < va.size(); ++v) {
            const double z = water.mesh().bed[v];
            if (!va.alive[v] || z == va.height[v]) continue;
            const double change = va.lumped_area[v] * (z - va.height[v]);
            sand_moved += std::max(0.0, -change);
            volume_change += change;
            moved.push_back(VertexId{static_cast<std::uint32_t>(v)});
            heights.push_back(z);
        }
        tin.set_heights(moved, heights);
    }
    std::size_t wetted = 0;
    double max_depth = 0.0;
    const auto moisture = static_cast<float>(op.wet_moisture);
    for (std::size_t v = 0; v < deepest.size(); ++v) {
        max_depth = std::max(max_depth, deepest[v]);
        if (deepest[v] < op.wet_depth) continue;
        const VertexId id{static_cast<std::uint32_t>(v)};
        if (!tin.is_alive(id)) continue;
        ++wetted;
        if (tin.vertices().moisture[v] < moisture) tin.set_moisture(id, moisture);
    }
    return {{"seconds", op.seconds},          {"steps", steps},
            {"added_m3", sources.added},      {"evaporated_m3", sources.evaporated},
            {"left_m3", water.volume_left()}, {"water_m3", water.volume()},
            {"wetted_vertices", wetted},      {"max_depth_m", max_depth},
            {"sand_moved_m3", sand_moved},    {"volume_change", volume_change}};
}

}  // namespace sandtin
