#include "io/script_water.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tin/vertex_arrays.hpp"
#include "water/live_water.hpp"
#include "water/sediment_transport.hpp"
#include "water/shallow_water.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/wet_edge_split.hpp"

namespace sandtin {

namespace {

Rain parse_rain(const nlohmann::json& object, const std::string& context) {
    JsonFields r(object, context);
    Rain rain;
    rain.mm_per_hour = r.in_range("mm_per_hour", 0.0, 0.0, 1e4);
    if (const auto disc = r.disc("for rain on a disc")) {
        rain.centre = disc->centre;
        rain.radius = disc->radius;
    }
    r.reject_unknown();
    return rain;
}

Nozzle parse_nozzle(const nlohmann::json& object, const std::string& context) {
    JsonFields n(object, context);
    Nozzle nozzle;
    nozzle.at = n.point("at");
    nozzle.litres_per_second = n.in_range("litres_per_second", 0.0, 0.0, 1e4);
    nozzle.radius = n.in_range("radius", 0.0, 0.0, 1e3);
    n.reject_unknown();
    return nozzle;
}

/// The moisture fields a "water" or "dry" operation shares; the defaults are the engine's.
MoistureSettings parse_moisture_settings(JsonFields& f) {
    MoistureSettings s;
    // Up to 1e-3 m²/s: beyond any soil-water diffusivity, and each tenfold costs ten times
    // the sub-steps.
    s.diffusivity = f.in_range("diffusivity", s.diffusivity, 0.0, 1e-3);
    s.drying_half_life = f.positive("drying_half_life", s.drying_half_life);
    return s;
}

nlohmann::json moisture_report(const MoistureReport& r, const Tin& tin) {
    nlohmann::json wettest = nullptr;
    if (r.wettest.valid()) {
        const Vec2 at = tin.position(r.wettest);
        wettest = {
            {"vertex", r.wettest.value}, {"at", {at.x, at.y}}, {"moisture", r.wettest_moisture}};
    }
    return {{"seconds", r.seconds},
            {"sub_steps", r.sub_steps},
            {"vertices_computed", r.vertices_computed},
            {"vertices_changed", r.vertices_changed},
            {"vertices_slowed", r.vertices_slowed},
            {"moisture_before_m2", r.total_before},
            {"moisture_after_m2", r.total_after},
            {"wettest", wettest}};
}

/// The "water" operation's sources: "rain" (one or an array) and "nozzles".
void parse_sources(JsonFields& f, WaterSources& sources) {
    if (const nlohmann::json* rain = f.get("rain")) {
        const std::string context = f.context() + ": rain";
        if (rain->is_array()) {
            for (std::size_t k = 0; k < rain->size(); ++k)
                sources.rain.push_back(
                    parse_rain((*rain)[k], context + "[" + std::to_string(k) + "]"));
        } else {
            sources.rain.push_back(parse_rain(*rain, context));
        }
    }
    if (const nlohmann::json* nozzles = f.get("nozzles")) {
        if (!nozzles->is_array()) f.fail_field("nozzles", "must be an array of nozzles");
        for (std::size_t k = 0; k < nozzles->size(); ++k)
            sources.nozzles.push_back(
                parse_nozzle((*nozzles)[k], f.context() + ": nozzles[" + std::to_string(k) + "]"));
    }
    if (sources.rain.empty() && sources.nozzles.empty())
        f.fail(
            "give 'rain' or 'nozzles': water needs a source (\"flow\" runs the water "
            "already on the terrain)");
}

/// The "rain" operation's source: one rain, its fields at the operation's top level.
void parse_top_level_rain(JsonFields& f, WaterSources& sources) {
    Rain rain;
    rain.mm_per_hour = f.in_range("mm_per_hour", 0.0, 0.0, 1e4);
    if (!(rain.mm_per_hour > 0.0)) f.fail_field("mm_per_hour", "must be a positive rate");
    if (const auto disc = f.disc("for rain on a disc")) {
        rain.centre = disc->centre;
        rain.radius = disc->radius;
    }
    sources.rain.push_back(rain);
}

}  // namespace

WaterOp parse_water_op(JsonFields& f, WaterOpKind kind) {
    WaterOp op;
    op.seconds = f.in_range("seconds", 0.0, 0.0, 1e6);
    if (!(op.seconds > 0.0)) f.fail_field("seconds", "must be a positive number of seconds");
    const std::string until = f.choice("until", "seconds", {"seconds", "dry", "rest"});
    op.until = until == "dry"    ? WaterStop::Dry
               : until == "rest" ? WaterStop::Rest
                                 : WaterStop::Seconds;
    if (op.until != WaterStop::Rest && f.has("rest_rate"))
        f.fail_field("rest_rate", "applies with \"until\": \"rest\"");
    if (op.until != WaterStop::Dry && f.has("rest_depth"))
        f.fail_field("rest_depth", "applies with \"until\": \"dry\"");
    op.rest_rate = f.positive("rest_rate", op.rest_rate);
    op.rest_depth = f.positive("rest_depth", op.rest_depth);
    if (kind == WaterOpKind::Water) parse_sources(f, op.sources);
    if (kind == WaterOpKind::Rain) parse_top_level_rain(f, op.sources);
    if (kind == WaterOpKind::Flow) {
        for (const char* source : {"rain", "nozzles"}) {
            if (f.has(source))
                f.fail_field(source, "adds water, which a \"flow\" does not: use \"water\"");
        }
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
    const std::string scheme = f.choice("scheme", "pipes", {"pipes", "shallow_water"});
    op.scheme = scheme == "pipes" ? WaterScheme::Pipes : WaterScheme::ShallowWater;
    if (op.scheme == WaterScheme::Pipes && f.has("manning"))
        f.fail_field("manning",
                     "applies to \"scheme\": \"shallow_water\"; the pipes take 'friction'");
    if (op.scheme == WaterScheme::ShallowWater && f.has("friction"))
        f.fail_field("friction", "applies to the pipes; \"shallow_water\" takes 'manning'");
    op.friction = f.in_range("friction", op.friction, 0.0, 1e3);
    op.manning = f.in_range("manning", op.manning, 0.0, 1.0);
    op.wet_moisture = f.in_range("wet_moisture", op.wet_moisture, 0.0, 1.0);
    op.wet_depth = f.positive("wet_depth", op.wet_depth);
    op.erode = f.boolean("erode", false);
    if (!op.erode && f.has("label_depth"))
        f.fail_field("label_depth", "applies with \"erode\": true");
    op.label_depth = f.positive("label_depth", op.label_depth);
    op.detail = f.in_range("detail", 0.0, 0.0, 1e4);
    op.moisture = parse_moisture_settings(f);
    f.reject_unknown();
    return op;
}

namespace {

/// What the water did, whichever scheme ran.
struct Flow {
    std::size_t steps = 0;
    double seconds = 0.0;  ///< s run
    const char* stopped = "seconds";
    double start = 0.0;  ///< m³ on the terrain at the start
    SourceReport sources;
    std::vector<double> deepest;  ///< per vertex, m
    double left = 0.0, water = 0.0, sand_moved = 0.0, volume_change = 0.0;
    std::size_t relabelled = 0;  ///< vertices that took the material of the sand laid on them
    std::size_t refined = 0;     ///< vertices the detail added under the water
};

/// No vertex holds `depth` of water or more.
template <class Water>
bool is_dry(const Water& water, double depth) {
    for (std::size_t v = 0; v < water.vertex_count(); ++v)
        if (water.depth(v) >= depth) return false;
    return true;
}

/// The largest depth change since `before` (m).
template <class Water>
double fastest_change(const Water& water, const std::vector<double>& before) {
    double fastest = 0.0;
    for (std::size_t v = 0; v < before.size(); ++v)
        fastest = std::max(fastest, std::abs(water.depth(v) - before[v]));
    return fastest;
}

/// Takes the films a dry terrain still holds off it; returns their volume (m³).
template <class Water>
double clear_films(Water& water) {
    double volume = 0.0;
    for (std::size_t v = 0; v < water.vertex_count(); ++v) {
        if (water.depth(v) == 0.0) continue;
        volume += water.mesh().area[v] * water.depth(v);
        water.set_depth(v, 0.0);
    }
    return volume;
}

/// Settles what the water still carries and writes the beds into the terrain (journaled, so
/// the GPU mirror and undo see it), counting the sand moved; sand laid at least label_depth
/// thick takes the material it came from.
template <class Water>
void write_sand(Water& water, SedimentTransport& sediment, const WaterOp& op, Tin& tin,
                Flow& flow) {
    sediment.settle_all(water);
    std::vector<VertexId> moved;
    std::vector<double> heights;
    const VertexArrays& va = tin.vertices();
    std::vector<std::pair<VertexId, std::uint16_t>> relabelled;
    for (std::size_t v = 0; v < water.vertex_count(); ++v) {
        const double z = water.mesh().bed[v];
        if (!va.alive[v] || z == va.height[v]) continue;
        const double change = va.lumped_area[v] * (z - va.height[v]);
        flow.sand_moved += std::max(0.0, -change);
        flow.volume_change += change;
        moved.push_back(VertexId{static_cast<std::uint32_t>(v)});
        heights.push_back(z);
        // Sand laid down at least label_depth thick is of the material it came from:
        // gravel washed onto sand shows, and slides, as gravel.
        const std::uint16_t laid = sediment.deposited_material(v);
        if (z - va.height[v] >= op.label_depth && laid != va.material[v])
            relabelled.emplace_back(moved.back(), laid);
    }
    tin.set_heights(moved, heights);
    for (const auto& [id, material] : relabelled)
        tin.set_material(id, material);
    flow.relabelled += relabelled.size();
}

/// The water's depths into the terrain (journaled: saved, undone), where they differ.
template <class Water>
void write_depths(const Water& water, Tin& tin) {
    const VertexArrays& va = tin.vertices();
    for (std::size_t v = 0; v < water.vertex_count(); ++v) {
        if (va.alive[v] && va.water_depth[v] != water.depth(v))
            tin.set_water_depth(VertexId{static_cast<std::uint32_t>(v)}, water.depth(v));
    }
}

/// Steps between two looks for long edges under the water (with a detail length).
constexpr std::size_t kDetailEvery = 16;
/// Edges split at one look at most, as in the editor (live_water.hpp's kMaxWaterSplits).
constexpr std::size_t kDetailSplits = 2000;

/// Runs the operation on water built by make_water() from the terrain (again after the detail
/// refined it: the water restarts from rest there, as each operation does).
template <class Water, class Make>
Flow run_flow(Make make_water, const WaterOp& op, Tin& tin) {
    Flow flow;
    std::optional<Water> water;
    std::optional<SedimentTransport> sediment;
    double left_before = 0.0;  // m³ out through open sides by the water built before
    const auto build = [&] {
        water.emplace(make_water());
        open_borders(*water, tin.domain(), op.open);
        // The water the terrain holds (from earlier operations, or from before a refinement).
        load_water_depths(*water, tin);
        if (op.erode) {
            std::vector<double> rock = tin.vertices().bedrock;
            for (double& z : rock) {
                if (!(z > 0.5 * kNoBedrock)) z = -std::numeric_limits<double>::infinity();
            }
            sediment.emplace(water->mesh(), std::move(rock), SedimentOptions{},
                             tin.vertices().material);
        }
    };
    build();
    flow.start = water->volume();
    std::vector<double>& deepest = flow.deepest;
    deepest.assign(water->depths().begin(), water->depths().end());
    std::vector<double> before;
    double t = 0.0;
    while (t < op.seconds) {
        if (op.until == WaterStop::Dry && is_dry(*water, op.rest_depth)) {
            flow.stopped = "dry";
            break;
        }
        if (op.detail > 0.0 && flow.steps % kDetailEvery == 0) {
            // Detail where the water is: its long edges split, the water built again on the
            // refined terrain (what it carried settled first: the new water starts from rest).
            // Looked for in the water's own depths: the terrain's are written only to split.
            if (has_long_wet_edge(tin, water->depths(), op.detail, kFilmDepth)) {
                write_depths(*water, tin);
                if (sediment) write_sand(*water, *sediment, op, tin, flow);
                const std::vector<VertexId> born =
                    split_wet_edges(tin, op.detail, kDetailSplits, kFilmDepth);
                flow.refined += born.size();
                left_before += water->volume_left();
                build();
                deepest.resize(water->vertex_count(), 0.0);
                for (std::size_t v = 0; v < deepest.size(); ++v)
                    deepest[v] = std::max(deepest[v], water->depth(v));
            }
        }
        const double dt = std::min({water->stable_time_step(), kLongestSourceStep, op.seconds - t});
        const SourceReport r = apply_sources(*water, op.sources, dt);
        flow.sources.added += r.added;
        flow.sources.evaporated += r.evaporated;
        if (op.until == WaterStop::Rest)
            before.assign(water->depths().begin(), water->depths().end());
        water->step(dt);
        if (sediment) sediment->step(*water, dt);
        for (std::size_t v = 0; v < deepest.size(); ++v)
            deepest[v] = std::max(deepest[v], water->depth(v));
        t += dt;
        ++flow.steps;
        if (op.until == WaterStop::Rest && fastest_change(*water, before) < op.rest_rate * dt) {
            flow.stopped = "rest";
            break;
        }
    }
    if (op.until == WaterStop::Dry && flow.stopped == std::string_view("seconds") &&
        is_dry(*water, op.rest_depth))
        flow.stopped = "dry";
    if (flow.stopped == std::string_view("dry")) flow.sources.evaporated += clear_films(*water);
    flow.seconds = t;
    if (sediment) write_sand(*water, *sediment, op, tin, flow);
    flow.left = left_before + water->volume_left();
    flow.water = water->volume();
    // The water stays on the terrain for the next operation (journaled: saved, undone).
    write_depths(*water, tin);
    return flow;
}

}  // namespace

nlohmann::json run_water_op(const WaterOp& op, Tin& tin, std::vector<VertexId>* reached) {
    Flow flow;
    if (op.scheme == WaterScheme::Pipes) {
        VirtualPipeOptions options;
        options.friction = op.friction;
        flow = run_flow<VirtualPipes>([&] { return VirtualPipes(water_mesh_of(tin), options); }, op,
                                      tin);
    } else {
        ShallowWaterOptions options;
        options.manning = op.manning;
        flow = run_flow<ShallowWater>([&] { return ShallowWater(water_mesh_of(tin), options); }, op,
                                      tin);
    }
    const std::vector<double>& deepest = flow.deepest;
    std::size_t wetted = 0;
    double max_depth = 0.0;
    const auto moisture = static_cast<float>(op.wet_moisture);
    for (std::size_t v = 0; v < deepest.size(); ++v) {
        max_depth = std::max(max_depth, deepest[v]);
        const VertexId id{static_cast<std::uint32_t>(v)};
        if (reached && deepest[v] > 0.0 && tin.is_alive(id)) reached->push_back(id);
        if (deepest[v] < op.wet_depth) continue;
        if (!tin.is_alive(id)) continue;
        ++wetted;
        if (tin.vertices().moisture[v] < moisture) tin.set_moisture(id, moisture);
    }
    // Then the moisture spreads and dries over the same seconds.
    const MoistureReport spread = spread_and_dry_moisture(tin, flow.seconds, op.moisture);
    return {{"seconds", flow.seconds},
            {"stopped", flow.stopped},
            {"scheme", op.scheme == WaterScheme::Pipes ? "pipes" : "shallow_water"},
            {"steps", flow.steps},
            {"water_at_start_m3", flow.start},
            {"added_m3", flow.sources.added},
            {"evaporated_m3", flow.sources.evaporated},
            {"left_m3", flow.left},
            {"water_m3", flow.water},
            {"wetted_vertices", wetted},
            {"max_depth_m", max_depth},
            {"sand_moved_m3", flow.sand_moved},
            {"material_changed_vertices", flow.relabelled},
            {"refined_vertices", flow.refined},
            {"moisture", moisture_report(spread, tin)},
            {"volume_change", flow.volume_change}};
}

DryOp parse_dry_op(JsonFields& f) {
    DryOp op;
    op.seconds = f.in_range("seconds", 0.0, 0.0, 1e7);
    if (!(op.seconds > 0.0)) f.fail_field("seconds", "must be a positive number of seconds");
    op.moisture = parse_moisture_settings(f);
    f.reject_unknown();
    return op;
}

nlohmann::json run_dry_op(const DryOp& op, Tin& tin) {
    nlohmann::json report =
        moisture_report(spread_and_dry_moisture(tin, op.seconds, op.moisture), tin);
    report["volume_change"] = 0.0;  // moisture moves no sand
    return report;
}

}  // namespace sandtin
