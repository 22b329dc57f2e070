// Weathering from scripts (io/script_weather.hpp, and the brush's "weather" kind): a poured
// pile's crest wears and its sand settles lower with the volume kept; only a disc weathers
// when one is given; bad fields are named.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <variant>
#include <vector>

#include "io/script.hpp"
#include "support/tin_oracles.hpp"
#include "tin/vertex_arrays.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {
namespace script_weather_test {

std::string weather_error(const std::string& op) {
    try {
        parse_script("[" + op + "]", "weather.json", ".");
    } catch (const JsonInputError& e) {
        return e.what();
    }
    return "";
}

/// A terrain with a sharp-crested heap on it: 0.5 L poured in a narrow disc, not eroded.
struct Heap {
    Tin tin;
    SculptContext context;
};

Heap poured_heap() {
    const Script s = parse_script(R"({"version": 1,
        "settings": {"simplify": false},
        "terrain": {"size": [1, 1], "points": 4000, "seed": 9},
        "operations": [{"op": "pour", "at": [0.4, 0.5], "volume": 0.0005, "radius": 0.05}]})",
                                  "heap.json", ".");
    Tin tin = make_script_terrain(*s.terrain);
    SculptContext context(tin.domain());
    run_script(s, tin, context);
    return {std::move(tin), std::move(context)};
}

TEST(ScriptWeather, AHeapsCrestWearsAndItsSandSettlesLowerWithTheVolumeKept) {
    Heap heap = poured_heap();
    const double top = test::highest_height(heap.tin), volume = heap.tin.volume();
    const Script s = parse_script(R"([{"op": "weather", "iterations": 20}])", "w.json", ".");
    const nlohmann::json r = run_script(s, heap.tin, heap.context).at(0);
    EXPECT_LT(test::highest_height(heap.tin), top);
    EXPECT_GT(r.at("vertices_worn").get<int>(), 0);
    EXPECT_GT(r.at("volume_moved_m3").get<double>(), 0.0);
    EXPECT_EQ(r.at("iterations").get<int>(), 20);
    EXPECT_NEAR(heap.tin.volume(), volume, 1e-12 * volume);
    EXPECT_NEAR(r.at("volume_change").get<double>(), 0.0, 1e-12 * volume);
}

TEST(ScriptWeather, OnlyTheGivenDiscWeathers) {
    // Two heaps; weathering a disc round the first leaves the second as it was.
    Heap heap = poured_heap();
    const Script second = parse_script(
        R"([{"op": "pour", "at": [0.75, 0.5], "volume": 0.0005, "radius": 0.05}])", "p.json", ".");
    run_script(second, heap.tin, heap.context);
    const std::vector<double> before = heap.tin.vertices().height;
    const Script s =
        parse_script(R"([{"op": "weather", "iterations": 5, "centre": [0.4, 0.5], "radius": 0.1}])",
                     "w.json", ".");
    run_script(s, heap.tin, heap.context);
    const VertexArrays& va = heap.tin.vertices();
    int near_changed = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || v >= before.size()) continue;
        const double d = length(va.position[v] - Vec2{0.4, 0.5});
        if (d > 0.2) {
            EXPECT_EQ(va.height[v], before[v]) << "at " << d << " m";
        }
        if (d < 0.1 && va.height[v] != before[v]) ++near_changed;
    }
    EXPECT_GT(near_changed, 10);
}

TEST(ScriptWeather, TheWeatherBrushWearsTheHeapUnderIt) {
    Heap heap = poured_heap();
    const double top = test::highest_height(heap.tin), volume = heap.tin.volume();
    const Script s = parse_script(
        R"([{"op": "brush", "kind": "weather", "strength": 1, "radius": 0.08,
             "path": [[0.35, 0.5], [0.45, 0.5]]}])",
        "b.json", ".");
    const auto& brush = std::get<BrushOp>(s.steps.at(0).operation);
    EXPECT_EQ(brush.settings.kind, BrushKind::Weather);
    run_script(s, heap.tin, heap.context);
    EXPECT_LT(test::highest_height(heap.tin), top);
    EXPECT_NEAR(heap.tin.volume(), volume, 1e-9 * volume);
}

TEST(ScriptWeather, BadFieldsAreNamed) {
    EXPECT_NE(weather_error(R"({"op": "weather", "iterations": 0})").find("iterations"),
              std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "weather", "strength": 2})").find("strength"),
              std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "weather", "power": 0.5})").find("power"), std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "weather", "centre": [0, 0]})").find("radius"),
              std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "weather", "radius": -1, "centre": [0, 0]})").find("radius"),
              std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "weather", "rate": 1})").find("rate"), std::string::npos);
    EXPECT_NE(weather_error(R"({"op": "brush", "kind": "weather", "strength": 1.5, "at": [0, 0]})")
                  .find("strength"),
              std::string::npos);
}

}  // namespace script_weather_test
}  // namespace
}  // namespace sandtin
