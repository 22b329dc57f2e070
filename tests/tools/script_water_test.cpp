// The script's "water" operation (io/script_water.hpp): rain on a disc wets the sand under it
// and not the sand far from it, adds exactly what its rate says (the lumped areas of the
// vertices it falls on x the rate x the time), and bad fields are named. Its moisture then
// spreads and dries (water/moisture_diffusion.hpp), as over a "dry" operation: a wall of wet
// sand stands at an angle dry sand cannot hold, and slides to the dry angle once it has dried.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "io/script.hpp"
#include "physics/material.hpp"
#include "support/tin_oracles.hpp"
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
                        "wet_moisture": 0.8, "diffusivity": 0, "drying_half_life": 1e30}]})");
    // Without spreading, and drying by a factor that rounds to 1, the moisture is the wetting's.
    const WaterOp& op = std::get<WaterOp>(s.steps.at(0).operation);
    EXPECT_EQ(op.sources.rain.size(), 1u);
    EXPECT_EQ(op.moisture.diffusivity, 0.0);
    EXPECT_EQ(op.moisture.drying_half_life, 1e30);
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
    EXPECT_EQ(report.at("moisture").at("vertices_changed").get<std::size_t>(), 0u);
    EXPECT_EQ(report.at("moisture").at("wettest").at("moisture").get<double>(), 0.8f);
}

TEST(ScriptWater, TheMoistureTheWaterLeavesSpreadsAndDriesOverItsSeconds) {
    // Drying is the same factor everywhere, so it commutes with the spreading (which
    // conserves sum A m): whatever the spreading did, the sum after is the sum the wetting
    // left times 2^(-t / T). Here t = T: half.
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 3000, "seed": 5, "sand_depth": 0.05},
        "operations": [{"op": "water", "seconds": 4,
                        "rain": {"mm_per_hour": 3600, "centre": [0.5, 0.5], "radius": 0.15},
                        "wet_moisture": 0.8, "diffusivity": 1e-4, "drying_half_life": 4}]})");
    Tin tin = make_script_terrain(*s.terrain);
    SculptContext context(tin.domain());
    const nlohmann::json report = run_script(s, tin, context).at(0);
    const nlohmann::json& moisture = report.at("moisture");
    const double wetted = moisture.at("moisture_before_m2").get<double>();
    EXPECT_GT(wetted, 0.8 * 0.05);  // 0.8 over the disc's 0.07 m² and more
    // Up to float rounding (2^-24 of it) and the moisture below 1e-6 that drying clears at
    // the end (at most 1e-6 x the 1 m² of the terrain).
    EXPECT_NEAR(test::brute_force_moisture(tin), 0.5 * wetted, std::ldexp(wetted, -24) + 1e-6);
    EXPECT_NEAR(moisture.at("moisture_after_m2").get<double>(), test::brute_force_moisture(tin),
                1e-12 * wetted);
    EXPECT_LE(moisture.at("wettest").at("moisture").get<double>(), 0.4 * (1.0 + 1e-6));
    EXPECT_GT(moisture.at("vertices_changed").get<std::size_t>(),
              report.at("wetted_vertices").get<std::size_t>());
}

/// The steepest face gradient |grad h| (m/m) of the terrain, from each triangle's plane.
double steepest_face(const Tin& tin) {
    double steepest = 0.0;
    for (const std::array<VertexId, 3>& t : tin.triangles()) {
        const Vec2 a = tin.position(t[0]), b = tin.position(t[1]), c = tin.position(t[2]);
        const double za = tin.height(t[0]), zb = tin.height(t[1]), zc = tin.height(t[2]);
        // The normal (b - a) x (c - a) in 3D: |grad h| = |(n_x, n_y)| / |n_z|.
        const Vec2 u = b - a, v = c - a;
        const double nx = u.y * (zc - za) - (zb - za) * v.y;
        const double ny = (zb - za) * v.x - u.x * (zc - za);
        steepest = std::max(steepest, std::hypot(nx, ny) / std::abs(cross(u, v)));
    }
    return steepest;
}

// A wall of wet sand stands at an angle dry sand cannot hold; once it has dried it slides to
// the dry angle. The wall: a plateau, a 38-degree face 0.2 m wide, a floor, on a regular grid
// whose lines follow the creases (so every triangle lies in one of the three planes), all
// sand (no bedrock). The presets' sand stands at 32 degrees dry and about 44 at the painted
// moisture 0.25 (physics/material.hpp).
TEST(ScriptWater, AWallOfWetSandStandsUntilItDriesAndThenSlidesToTheDryAngle) {
    const double deg = std::numbers::pi / 180.0;
    const double face = std::tan(38.0 * deg), top = 0.2 * face;
    const MaterialTable presets = MaterialTable::presets();
    ASSERT_GT(presets.at(0).talus_slope(0.25), 1.05 * face);
    ASSERT_LT(presets.at(0).talus_slope(0.0), face);
    Tin tin = Tin::regular_grid(Rect::from_size(1, 1), 50, 50, [&](Vec2 p) {
        return std::clamp(top - face * (p.x - 0.4), 0.0, top);
    });
    ASSERT_NEAR(steepest_face(tin), face, 1e-9 * face);
    for (VertexId v : tin.vertices_in_disc({0.5, 0.5}, 1.0))
        tin.set_moisture(v, 0.25f);
    const std::vector<double> built = tin.vertices().height;
    const double volume = tin.volume();
    SculptContext context(tin.domain());
    // Wet, it is at rest as built.
    const nlohmann::json wet =
        run_script(parse_water_script(R"([{"op": "erode", "until_rest": true}])"), tin, context);
    EXPECT_TRUE(wet.at(0).at("at_rest").get<bool>());
    for (std::size_t v = 0; v < built.size(); ++v)
        ASSERT_EQ(tin.vertices().height[v], built[v]) << "vertex " << v << " moved";
    EXPECT_NEAR(steepest_face(tin), face, 1e-9 * face);
    // Dried (25 half-lives take 0.25 below 1e-6: dry), it slides to the dry angle.
    const double crest_before = *tin.height_at({0.4, 0.5});
    const nlohmann::json dried =
        run_script(parse_water_script(R"([{"op": "dry", "seconds": 15000, "drying_half_life": 600},
                               {"op": "erode", "until_rest": true}])"),
                   tin, context);
    EXPECT_EQ(dried.at(0).at("moisture_after_m2").get<double>(), 0.0);
    EXPECT_TRUE(dried.at(0).at("wettest").is_null());
    EXPECT_EQ(test::brute_force_moisture(tin), 0.0);
    EXPECT_TRUE(dried.at(1).at("at_rest").get<bool>());
    EXPECT_LE(steepest_face(tin), std::tan(32.0 * deg) * (1.0 + 1e-3));
    // At 32 degrees through the same volume the face pivots about its middle: the crest at
    // x = 0.4 comes down by 0.025 tan(32 deg) = 1.6 cm.
    EXPECT_LT(*tin.height_at({0.4, 0.5}), crest_before - 0.01);
    EXPECT_NEAR(tin.volume(), volume, 1e-12 * volume);
}

/// A nozzle on flat sand 2 cm over the rock: its jet digs a hole and the water drops the sand
/// around it as it spreads and slows, under `scheme` for `seconds`.
void a_nozzle_erodes(const std::string& scheme, double seconds) {
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 2000, "seed": 8, "sand_depth": 0.02},
        "operations": [{"op": "water", "seconds": )" +
                                        std::to_string(seconds) +
                                        R"(, "erode": true, "scheme": ")" + scheme + R"(",
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
    // The water's own balance: what stands and what left is what came, none evaporated.
    EXPECT_NEAR(report.at("water_m3").get<double>() + report.at("left_m3").get<double>(),
                0.5e-3 * seconds, 1e-12);
    EXPECT_EQ(report.at("scheme").get<std::string>(), scheme);
    ASSERT_TRUE(tin.check_valid().ok());
}

TEST(ScriptWater, WaterThatErodesMovesSandHoldingItsVolumeAndNeverCutsTheRock) {
    a_nozzle_erodes("pipes", 5.0);
}

TEST(ScriptWater, UnderTheShallowWaterSchemeTooErodingWaterHoldsTheSandsVolume) {
    a_nozzle_erodes("shallow_water", 1.0);
}

TEST(ScriptWater, SandTheWaterLaysDownTakesTheMaterialItCameFrom) {
    // Gravel painted round a nozzle on sand: the jet washes gravel out and lays it beyond the
    // painted disc, where those vertices become gravel; every vertex relabelled was built up
    // at least label_depth (0.1 mm here: the jet spreads what it carries thinly), and the
    // report counts them.
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 2000, "seed": 8, "sand_depth": 0.02},
        "operations": [
          {"op": "brush", "kind": "paint", "material": 2, "at": [0.5, 0.5], "radius": 0.08},
          {"op": "water", "seconds": 5, "erode": true, "label_depth": 0.0001,
           "nozzles": [{"at": [0.5, 0.5], "litres_per_second": 0.5}]}]})");
    Tin tin = make_script_terrain(*s.terrain);
    SculptContext context(tin.domain());
    Script paint = s;
    paint.steps.resize(1);
    run_script(paint, tin, context);
    const std::vector<double> height = tin.vertices().height;
    const std::vector<std::uint16_t> material = tin.vertices().material;
    Script water = s;
    water.steps.erase(water.steps.begin());
    const nlohmann::json report = run_script(water, tin, context).at(0);
    const VertexArrays& va = tin.vertices();
    std::size_t changed = 0, gravel_outside = 0;
    for (std::size_t v = 0; v < material.size(); ++v) {
        if (!va.alive[v] || va.material[v] == material[v]) continue;
        ++changed;
        EXPECT_GE(va.height[v] - height[v], 1e-4 - 1e-15) << v;
        if (va.material[v] == 2 && length(va.position[v] - Vec2{0.5, 0.5}) > 0.08) ++gravel_outside;
    }
    EXPECT_EQ(report.at("material_changed_vertices").get<std::size_t>(), changed);
    EXPECT_GT(gravel_outside, 0u);
}

TEST(ScriptWater, DetailRefinesUnderTheWaterKeepingBothVolumesAndGoesOnceItIsDry) {
    // A coarse flat sandbox (60 random points: edges of 10 to 20 cm) rained on in its middle
    // with a 4 cm detail: the edges under the water are split as it stands there, the water's
    // balance and the sand's volume exact. Then the water evaporates away, and the ground it
    // left, flat and dry, is simplified: the detail goes again.
    const Script s = parse_water_script(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 60, "seed": 7, "sand_depth": 0.05},
        "operations": [
          {"op": "water", "seconds": 3, "detail": 0.04,
           "rain": {"mm_per_hour": 3600, "centre": [0.5, 0.5], "radius": 0.25}},
          {"op": "flow", "seconds": 600, "until": "dry", "detail": 0.04,
           "evaporation_mm_per_hour": 10000}]})");
    EXPECT_EQ(std::get<WaterOp>(s.steps.at(0).operation).detail, 0.04);
    Tin tin = make_script_terrain(*s.terrain);
    const std::size_t coarse = tin.vertex_count();
    const double sand = tin.volume();
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const nlohmann::json& rain = reports.at(0);
    const std::size_t refined = rain.at("refined_vertices").get<std::size_t>();
    EXPECT_GT(refined, 20u);
    const double added = rain.at("added_m3").get<double>();
    EXPECT_NEAR(rain.at("water_m3").get<double>(),
                rain.at("water_at_start_m3").get<double>() + added -
                    rain.at("evaporated_m3").get<double>() - rain.at("left_m3").get<double>(),
                1e-12 * added);
    // The water was there while the refinement ran: what stood 1 mm deep has its 4 cm edges.
    const nlohmann::json& dried = reports.at(1);
    EXPECT_EQ(dried.at("stopped").get<std::string>(), "dry");
    EXPECT_NEAR(dried.at("evaporated_m3").get<double>(), rain.at("water_m3").get<double>(),
                1e-12 * added);
    // Dry and flat: the simplifier took the detail away again (and flat ground the water
    // covered besides), with the sand's volume unchanged throughout.
    EXPECT_GE(dried.at("simplified_vertices").get<std::size_t>(), refined);
    EXPECT_LE(tin.vertex_count(), coarse);
    EXPECT_NEAR(tin.volume(), sand, 1e-12 * sand);
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
                              "detail": -0.01})")
                  .find("detail"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1,
                              "nozzles": [{"at": [0.5, 0.5], "litres_per_second": 1,
                                           "radius": -0.01}]})")
                  .find("radius"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "colour": "blue"})")
                  .find("colour"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "manning": 0.03})")
                  .find("manning"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "scheme": "shallow_water", "friction": 1})")
                  .find("friction"),
              std::string::npos);
    EXPECT_NE(water_error(R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5},
                              "scheme": "lattice_boltzmann"})")
                  .find("scheme"),
              std::string::npos);
    EXPECT_EQ(water_error(R"({"op": "water", "seconds": 2,
                              "nozzles": [{"at": [0.5, 0.5], "litres_per_second": 0.1}],
                              "open_sides": ["west", "north"], "evaporation_mm_per_hour": 1})"),
              "");
}

TEST(ScriptWater, BadFieldsOfADryAreNamed) {
    const Script s = parse_water_script(
        R"([{"op": "dry", "seconds": 60, "diffusivity": 2e-7, "drying_half_life": 100}])");
    const DryOp& op = std::get<DryOp>(s.steps.at(0).operation);
    EXPECT_EQ(op.seconds, 60.0);
    EXPECT_EQ(op.moisture.diffusivity, 2e-7);
    EXPECT_EQ(op.moisture.drying_half_life, 100.0);
    const DryOp defaults = std::get<DryOp>(
        parse_water_script(R"([{"op": "dry", "seconds": 1}])").steps.at(0).operation);
    EXPECT_EQ(defaults.moisture.diffusivity, MoistureSettings{}.diffusivity);
    EXPECT_EQ(defaults.moisture.drying_half_life, MoistureSettings{}.drying_half_life);
    const std::pair<const char*, const char*> bad[] = {
        {R"({"op": "dry"})", "seconds"},
        {R"({"op": "dry", "seconds": 0})", "seconds"},
        {R"({"op": "dry", "seconds": -5})", "seconds"},
        {R"({"op": "dry", "seconds": "long"})", "seconds"},
        {R"({"op": "dry", "seconds": 1, "diffusivity": -1e-7})", "diffusivity"},
        {R"({"op": "dry", "seconds": 1, "diffusivity": 1})", "diffusivity"},
        {R"({"op": "dry", "seconds": 1, "drying_half_life": 0})", "drying_half_life"},
        {R"({"op": "dry", "seconds": 1, "drying_half_life": -60})", "drying_half_life"},
        {R"({"op": "dry", "seconds": 1, "rain": {"mm_per_hour": 5}})", "rain"},
        {R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5}, "diffusivity": -1})",
         "diffusivity"},
        {R"({"op": "water", "seconds": 1, "rain": {"mm_per_hour": 5}, "drying_half_life": 0})",
         "drying_half_life"}};
    for (const auto& [text, field] : bad) {
        const std::string what = water_error(text);
        EXPECT_NE(what.find(field), std::string::npos) << text << ": " << what;
        EXPECT_NE(what.find("operation"), std::string::npos) << what;
    }
}

}  // namespace script_water_test
}  // namespace
}  // namespace sandtin
