// The script's "water" operation (io/script_water.hpp): rain on a disc wets the sand under it
// and not the sand far from it, adds exactly what its rate says (the lumped areas of the
// vertices it falls on x the rate x the time), and bad fields are named.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "io/script.hpp"
#include "tin/vertex_arrays.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {
namespace script_water_test {

Script parse_water_script(const std::string& text) {
    return parse_script(text, "water.json", ".");
}

std::string water_error(const std::string& op) {
    try {
        parse_water_script("[" + op + "]");
    } catch (const JsonInputError& e) {
        return e.what();
    }
    return "";
}

TEST(ScriptWater, RainOnADiscWetsTheSandUnderItAndAddsWhatItsRateSays) {
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 3000, "seed": 5, "sand_depth": 0.05},
        "operations": [{"op": "water", "seconds": 4,
                        "rain": {"mm_per_hour": 3600, "centre": [0.5, 0.5], "radius": 0.15},
                        "wet_moisture": 0.8}]})");
    const WaterOp& op = std::get<WaterOp>(s.steps.at(0).operation);
    EXPECT_EQ(op.sources.rain.size(), 1u);
    Tin tin = make_script_terrain(*s.terrain);
    double rained_on = 0.0;  // m²: the lumped areas of the vertices in the disc
    const VertexArrays& va = tin.vertices();
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v] && length(va.position[v] - Vec2{0.5, 0.5}) <= 0.15)
            rained_on += va.lumped_area[v];
    }
    const double heights_before = tin.volume();
    SculptContext context(tin.domain());
    const nlohmann::json report = run_script(s, tin, context).at(0);
    // 1 mm/s for 4 s on the disc's vertices.
    const double added = rained_on * 1e-3 * 4.0;
    EXPECT_NEAR(report.at("added_m3").get<double>(), added, 1e-12 * added);
    // Walls all round and no evaporation: all of it is still there.
    EXPECT_NEAR(report.at("water_m3").get<double>(), added, 1e-12 * added);
    EXPECT_EQ(report.at("left_m3").get<double>(), 0.0);
    EXPECT_EQ(tin.volume(), heights_before);  // water moves no sand
    std::size_t wet_inside = 0, inside = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = length(va.position[v] - Vec2{0.5, 0.5});
        if (r < 0.12) {
            ++inside;
            wet_inside += va.moisture[v] == 0.8f ? 1 : 0;
        }
        if (r > 0.4) {
            EXPECT_EQ(va.moisture[v], 0.0f) << "far from the rain at " << v;
        }
    }
    EXPECT_EQ(wet_inside, inside);
    EXPECT_GE(report.at("wetted_vertices").get<std::size_t>(), inside);
}

TEST(ScriptWater, WaterThatErodesMovesSandHoldingItsVolumeAndNeverCutsTheRock) {
    // A nozzle on flat sand 2 cm over the rock: its jet digs a hole and the water drops the
    // sand around it as it spreads and slows.
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 2000, "seed": 8, "sand_depth": 0.02},
        "operations": [{"op": "water", "seconds": 5, "erode": true,
                        "nozzles": [{"at": [0.5, 0.5], "litres_per_second": 0.5}]}]})");
    EXPECT_TRUE(std::get<WaterOp>(s.steps.at(0).operation).erode);
    Tin tin = make_script_terrain(*s.terrain);
    const std::vector<double> before = tin.vertices().height;
    const double volume = tin.volume();
    SculptContext context(tin.domain());
    const nlohmann::json report = run_script(s, tin, context).at(0);
    EXPECT_GT(report.at("sand_moved_m3").get<double>(), 1e-6);
    // Exact to rounding against the 0.02 m³ of sand (the surface is at z = 0, so its volume
    // above the datum is 0 before and after).
    EXPECT_NEAR(tin.volume(), volume, 1e-12 * 0.02);
    EXPECT_NEAR(report.at("volume_change").get<double>(), 0.0, 1e-12 * 0.02);
    const VertexArrays& va = tin.vertices();
    double deepest = 0.0, highest = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        EXPECT_GE(va.height[v], va.bedrock[v]) << v;
        deepest = std::max(deepest, before[v] - va.height[v]);
        highest = std::max(highest, va.height[v] - before[v]);
    }
    EXPECT_GT(deepest, 1e-4) << "no hole under the jet";
    EXPECT_GT(highest, 0.0) << "the sand was dropped nowhere";
    ASSERT_TRUE(tin.check_valid().ok());
}

TEST(ScriptWater, BadFieldsAreNamed) {
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1})").find("source"), std::string::npos);
    EXPECT_NE(
        water_error(R"({"op": "water", "seconds": 0, "rain": {"mm_per_hour": 5}})").find("seconds"),
        std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "open_sides": ["up"]})")
                  .find("open_sides"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1,
                              "rain": {"mm_per_hour": 5, "centre": [0.5, 0.5]}})")
                  .find("radius"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1,
                              "nozzles": [{"at": [0.5, 0.5], "litres_per_second": -1}]})")
                  .find("litres_per_second"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "colour": "blue"})")
                  .find("colour"),
              std::string::npos);
    EXPECT_EQ(water_error(R"({"op": "water", "seconds": 2,
                              "nozzles": [{"at": [0.5, 0.5], "litres_per_second": 0.1}],
                              "open_sides": ["west", "north"], "evaporation_mm_per_hour": 1})"),
              "");
}

}  // namespace script_water_test
}  // namespace
}  // namespace sandtin
