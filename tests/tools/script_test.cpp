// Sculpting scripts: parsing (both forms, line numbers), errors that name the line and the
// field, and running a script. Oracles: the script texts written here, with their line numbers
// counted by hand; volumes of pours known exactly.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "io/scene_materials.hpp"
#include "io/script.hpp"
#include "physics/cone.hpp"
#include "physics/face_slopes.hpp"
#include "physics/material.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tools/falloff.hpp"
#include "tools/tool_json.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {

Script parse(const std::string& text) {
    return parse_script(text, "script.json", ".");
}

/// The message of the JsonInputError a script raises ("" when it parses).
std::string error_of(const std::string& text) {
    try {
        parse(text);
    } catch (const JsonInputError& e) {
        return e.what();
    }
    return "";
}

TEST(Script, EveryFalloffNameGivesTheDocumentedFormula) {
    // The README's formulas at half the radius: constant 1, linear 1 - t, smooth
    // 1 - smoothstep(t), gaussian exp(-4.5 t^2).
    const std::pair<const char*, double> expected[] = {
        {"constant", 1.0}, {"linear", 0.5}, {"smooth", 0.5}, {"gaussian", std::exp(-1.125)}};
    for (const auto& [name, weight] : expected) {
        const Script s = parse(std::string(R"([{"op": "brush", "at": [0.5, 0.5], "falloff": ")") +
                               name + R"("}, {"op": "pour", "at": [0.5, 0.5], "volume": 1e-6,
                                  "falloff": ")" +
                               name + R"("}])");
        const auto& brush = std::get<BrushOp>(s.steps[0].operation);
        const auto& pour = std::get<PourOp>(s.steps[1].operation);
        EXPECT_DOUBLE_EQ(falloff_weight(brush.settings.falloff, 0.5), weight) << name;
        EXPECT_DOUBLE_EQ(falloff_weight(pour.settings.falloff, 0.5), weight) << name;
        EXPECT_STREQ(falloff_name(brush.settings.falloff), name);
    }
    EXPECT_NE(error_of(R"([{"op": "brush", "at": [0.5, 0.5], "falloff": "cubic"}])")
                  .find("expected one of: constant, linear, smooth, gaussian"),
              std::string::npos);
    EXPECT_FALSE(falloff_named("Smooth").has_value());  // names are matched exactly
}

TEST(Script, ArrayFormParsesEveryOperationWithItsLine) {
    const std::string text = R"([
  {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "depth": 0.01},
  {"op": "stroke", "tool": {"contour": "circle", "radius": 0.03}, "path": [[0.2, 0.2], [0.8, 0.3]], "spacing": 0.01, "bottom": 0.05},

  {"op": "pour", "at": [0.3, 0.7], "volume": 1e-5, "radius": 0.02},
  {"op": "remove", "path": [[0.6, 0.6], [0.705, 0.6]], "volume": 1e-6, "radius": 0.02},
  {
    "op": "brush", "kind": "smooth", "at": [0.4, 0.4], "radius": 0.05, "strength": 0.5
  },
  {"op": "simplify", "tolerance": 0.001}
]
)";
    const Script s = parse(text);
    ASSERT_EQ(s.steps.size(), 6u);
    EXPECT_FALSE(s.terrain.has_value());
    const std::vector<std::size_t> lines = {2, 3, 5, 6, 7, 10};
    for (std::size_t i = 0; i < s.steps.size(); ++i)
        EXPECT_EQ(s.steps[i].line, lines[i]) << "operation " << i + 1;
    EXPECT_EQ(s.steps[0].op_name, "stamp");
    EXPECT_EQ(s.steps[1].op_name, "stroke");
    EXPECT_EQ(s.steps[3].op_name, "remove");

    const auto& stamp_op = std::get<StampOp>(s.steps[0].operation);
    EXPECT_EQ(stamp_op.at, (Vec2{0.5, 0.5}));
    EXPECT_EQ(stamp_op.depth_mode, DepthMode::Relative);
    EXPECT_DOUBLE_EQ(stamp_op.depth, 0.01);
    EXPECT_DOUBLE_EQ(stamp_op.tool->spec().radius, 0.04);  // assets/tools/circle.json
    const auto& stroke_op = std::get<StrokeOp>(s.steps[1].operation);
    EXPECT_EQ(stroke_op.path.size(), 2u);
    EXPECT_DOUBLE_EQ(stroke_op.settings.spacing, 0.01);
    EXPECT_EQ(stroke_op.settings.depth_mode, DepthMode::Absolute);
    EXPECT_DOUBLE_EQ(stroke_op.settings.depth, 0.05);
    EXPECT_DOUBLE_EQ(stroke_op.tool->spec().radius, 0.03);
    const auto& pour_op = std::get<PourOp>(s.steps[2].operation);
    EXPECT_FALSE(pour_op.remove);
    ASSERT_EQ(pour_op.points.size(), 1u);
    EXPECT_DOUBLE_EQ(pour_op.volume, 1e-5);
    EXPECT_DOUBLE_EQ(pour_op.settings.radius, 0.02);
    // A removal along a path: points every spacing (default radius / 2 = 1 cm) over 10.5 cm.
    const auto& remove_op = std::get<PourOp>(s.steps[3].operation);
    EXPECT_TRUE(remove_op.remove);
    ASSERT_EQ(remove_op.points.size(), 11u);
    for (std::size_t k = 0; k < remove_op.points.size(); ++k)
        EXPECT_NEAR(remove_op.points[k].x, 0.6 + 0.01 * static_cast<double>(k), 1e-12);
    const auto& brush_op = std::get<BrushOp>(s.steps[4].operation);
    EXPECT_EQ(brush_op.settings.kind, BrushKind::Smooth);
    EXPECT_DOUBLE_EQ(brush_op.settings.strength, 0.5);
    const auto& simplify_op = std::get<SimplifyOp>(s.steps[5].operation);
    ASSERT_TRUE(simplify_op.tolerance.has_value());
    EXPECT_DOUBLE_EQ(*simplify_op.tolerance, 0.001);
}

TEST(Script, ObjectFormWithTerrainAndSettings) {
    const std::string text = R"({
  "version": 1,
  "terrain": {"size": [2, 1.5], "points": 500, "seed": 9, "height": 0.2},
  "settings": {"simplify_tolerance": 0.002, "keep_generations": 10, "simplify": false},
  "operations": [
    {"op": "pour", "at": [1.0, 0.7], "volume": 2e-5, "radius": 0.05},
    {"op": "stamp", "tool": {"asset": "lambda"}, "at": [0.5, 0.5], "angle": 0.3, "bottom": 0.15}
  ]
})";
    const Script s = parse(text);
    ASSERT_TRUE(s.terrain.has_value());
    EXPECT_EQ(s.terrain->size, (Vec2{2.0, 1.5}));
    EXPECT_EQ(s.terrain->points, 500u);
    EXPECT_EQ(s.terrain->seed, 9u);
    EXPECT_DOUBLE_EQ(s.terrain->height, 0.2);
    ASSERT_TRUE(s.simplify_tolerance && s.keep_generations && s.simplify);
    EXPECT_DOUBLE_EQ(*s.simplify_tolerance, 0.002);
    EXPECT_EQ(*s.keep_generations, 10u);
    EXPECT_FALSE(*s.simplify);
    ASSERT_EQ(s.steps.size(), 2u);
    EXPECT_EQ(s.steps[0].line, 6u);
    EXPECT_EQ(s.steps[1].line, 7u);
    const auto& stamp_op = std::get<StampOp>(s.steps[1].operation);
    EXPECT_EQ(stamp_op.depth_mode, DepthMode::Absolute);
    EXPECT_DOUBLE_EQ(stamp_op.depth, 0.15);
    EXPECT_DOUBLE_EQ(stamp_op.angle, 0.3);
    EXPECT_EQ(stamp_op.tool->spec().name, "lambda");
}

TEST(Script, AnOperationTheTerrainRefusesIsNamedByItsLine) {
    // A 5 cm tool on a 5 km terrain (stamp_test: too small to tell its contours apart).
    const Script s = parse(R"([
  {"op": "pour", "at": [2500, 2500], "volume": 1, "radius": 20},
  {"op": "stamp", "tool": {"asset": "circle", "radius": 0.05}, "at": [100, 100], "depth": 0.01}
])");
    Tin tin = Tin::random_points(Rect::from_size(5000, 5000), 500, 602, [](Vec2) { return 1.0; });
    SculptContext context(tin.domain());
    try {
        run_script(s, tin, context);
        ADD_FAILURE() << "the stamp ran";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("script.json:3: operation 2 (stamp): stamp: the tool is too small", 0),
                  0u)
            << m;
    }
}

// A stamp whose extrusion pushed sand over the terrain's edge says so, naming its line; the
// volume it reports lost is what the flat terrain lost (area times depth).
TEST(Script, AStampThatLosesItsExtrusionWarnsNamingItsLine) {
    const Script s = parse(R"([
  {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "bottom": 0.09},
  {"op": "stamp", "tool": {"radius": 5, "control_points": 64, "extrude": true},
   "at": [0.5, 0.5], "bottom": 0.08}
])");
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 500, 603, [](Vec2) { return 0.1; });
    SculptContext context(tin.domain());
    const double v0 = tin.volume();
    const nlohmann::json report = run_script(s, tin, context);
    ASSERT_EQ(report.size(), 2u);
    EXPECT_FALSE(report[0].contains("warning")) << report[0].dump();
    ASSERT_TRUE(report[1].contains("warning")) << report[1].dump();
    const std::string w = report[1]["warning"];
    EXPECT_EQ(w.rfind("script.json:3: operation 2 (stamp): extrusion had nowhere to put", 0), 0u)
        << w;
    // The second stamp leaves the whole 1 m² at its 8 cm floor; it lost all it cut.
    EXPECT_NEAR(tin.volume(), 0.08, 1e-12);
    const double before_second = v0 + report[0]["volume_change"].get<double>();
    EXPECT_NEAR(report[1]["undeposited_volume"].get<double>(), before_second - 0.08, 1e-12);
}

// Operations that change less than they ask for say so: a stamp and a stroke beside the
// terrain, a stamp no deeper than the surface, a pour beside it, a removal from a terrain
// whose sand is gone. Those that do their work say nothing.
TEST(Script, OperationsThatMissTheTerrainWarn) {
    const Script s = parse(R"([
  {"op": "stamp", "tool": {"asset": "circle"}, "at": [5, 5], "depth": 0.01},
  {"op": "stroke", "tool": {"asset": "circle"}, "path": [[5, 5], [6, 5]], "depth": 0.01},
  {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5]},
  {"op": "pour", "at": [5, 5], "volume": 0.001},
  {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.5, 0.5], "depth": 0.01},
  {"op": "pour", "at": [0.3, 0.3], "volume": 0.0001},
  {"op": "remove", "at": [0.7, 0.7], "volume": 1}
])");
    // 10 cm of sand over bedrock at 0: a removal can take at most 0.1 m³ from the 1 m².
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 500, 604, [](Vec2) { return 0.1; });
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i) {
        if (tin.is_alive(VertexId{i})) tin.set_bedrock(VertexId{i}, 0.0);
    }
    SculptContext context(tin.domain());
    const nlohmann::json report = run_script(s, tin, context);
    ASSERT_EQ(report.size(), 7u);
    const auto warning = [&](std::size_t k) { return report[k].value("warning", std::string()); };
    EXPECT_EQ(
        warning(0).rfind("script.json:2: operation 1 (stamp): no stamp changed the terrain", 0), 0u)
        << warning(0);
    EXPECT_EQ(
        warning(1).rfind("script.json:3: operation 2 (stroke): no stamp changed the terrain", 0),
        0u)
        << warning(1);
    EXPECT_NE(warning(2).find("no stamp changed the terrain"), std::string::npos) << warning(2);
    EXPECT_NE(warning(3).find("poured 0 m³ of the 0.001 m³ asked"), std::string::npos)
        << warning(3);
    EXPECT_EQ(warning(4), "") << report[4].dump();
    EXPECT_EQ(warning(5), "") << report[5].dump();
    EXPECT_NE(warning(6).find("of the 1 m³ asked: there is no more sand"), std::string::npos)
        << warning(6);
    EXPECT_LE(-report[6]["volume"].get<double>(), 0.1 + 1e-9);
}

TEST(Script, RunAppliesTheOperationsAndTheSettings) {
    const std::string text = R"({
  "settings": {"simplify_tolerance": 0.002, "keep_generations": 10},
  "operations": [
    {"op": "pour", "at": [0.5, 0.5], "volume": 3e-5, "radius": 0.04},
    {"op": "pour", "path": [[0.2, 0.2], [0.3, 0.2]], "volume": 2e-5, "radius": 0.02},
    {"op": "stamp", "tool": {"asset": "circle"}, "at": [0.7, 0.7], "bottom": 0.05}
  ]
})";
    const Script s = parse(text);
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 2000, 601, [](Vec2) { return 0.1; });
    SculptContext context(tin.domain());
    const double v0 = tin.volume();
    const nlohmann::json report = run_script(s, tin, context);
    EXPECT_DOUBLE_EQ(context.settings.simplify.tolerance, 0.002);
    EXPECT_EQ(context.settings.keep_generations, 10u);
    ASSERT_EQ(report.size(), 3u);
    EXPECT_EQ(report[0]["op"], "pour");
    EXPECT_EQ(report[2]["line"], 6);
    EXPECT_TRUE(tin.check_valid().ok());
    // The pours add exactly their volume; the flat stamp then removes its footprint down to
    // 5 cm: between the inner polygon's area and the outer's, times 5 cm.
    const Tool circle = Tool::build(load_tool_asset("circle"));
    const double inner = static_cast<double>(test::signed_area_ld(circle.shape().inner));
    const double outer = static_cast<double>(test::signed_area_ld(circle.shape().outer));
    const double dug = v0 + 5e-5 - tin.volume();
    EXPECT_GT(dug, inner * 0.05 * (1.0 - 1e-9));
    EXPECT_LT(dug, outer * 0.05);
    EXPECT_NEAR(*tin.height_at({0.7, 0.7}), 0.05, 1e-12);
}

TEST(Script, ACheckpointKeepsTheSessionsMetadataAndUnknownChunks) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("sandtin-checkpoint-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path checkpoint = dir / "ck.sandtin";
    const Script s = parse(R"([
  {"op": "pour", "at": [0.5, 0.5], "volume": 1e-5, "radius": 0.04},
  {"op": "save", "path": ")" +
                           checkpoint.string() + R"("}
])");
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 500, 603, [](Vec2) { return 0.1; });
    Session opened;
    opened.metadata_json = R"({"scene":"dunes","import":{"source":"bay.png"}})";
    opened.unknown_chunks[0x7A7A7A7Au] = {1, 2, 3};
    SculptContext context(tin.domain());
    run_script(s, tin, context, {}, &opened);
    const Session saved = load_session(checkpoint);
    EXPECT_EQ(nlohmann::json::parse(saved.metadata_json),
              nlohmann::json::parse(opened.metadata_json));
    EXPECT_EQ(saved.unknown_chunks, opened.unknown_chunks);
    // The checkpoint holds the terrain after the pour, not the opened session's (empty) one.
    EXPECT_EQ(Tin::from_snapshot(saved.terrain).vertex_count(), tin.vertex_count());
    EXPECT_DOUBLE_EQ(Tin::from_snapshot(saved.terrain).volume(), tin.volume());
    std::filesystem::remove_all(dir);
}

/// A 1 m terrain of 2000 random points: one plane rising at `slope` (rise over run) along x,
/// so every triangle's gradient is `slope` (a crease would not do: the random points' slivers
/// along the border that straddle it are far steeper, and the face rule relaxes them).
Tin ramp_terrain(double slope, std::uint64_t seed) {
    return Tin::random_points(Rect::from_size(1, 1), 2000, seed,
                              [&](Vec2 p) { return 0.5 + slope * p.x; });
}

/// The largest height change of a vertex since `before` (heights by id; vertices inserted
/// since, under ids beyond it, are not compared).
double largest_change(const Tin& tin, const std::vector<double>& before) {
    double moved = 0.0;
    for (VertexId v : test::live_ids(tin)) {
        if (v.index() < before.size())
            moved = std::max(moved, std::abs(tin.height(v) - before[v.index()]));
    }
    return moved;
}

// Painting moist sand paints its moisture too (the preset's default_moisture, 0.25, which the
// materials table documents as what the paint tool applies): a 40-degree slope painted moist
// stands (moist sand at 0.25 holds about 44 degrees), the same slope left dry slides to 32.
// "sand_depth" lays a flat bedrock under the script's terrain, so scripts (and `sandtin new
// --sand-depth`) can build what the editor's default scene has. Oracle: the bedrock is where it
// was asked for, a removal larger than the sand there digs down to it and no further, and the
// erosion that follows never exposes it.
TEST(Script, ATerrainsSandDepthLaysAFlatBedrockThatDiggingStopsAt) {
    const Script s = parse(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 3000, "seed": 4, "height": 0.1, "sand_depth": 0.02},
        "operations": [
          {"op": "remove", "at": [0.5, 0.5], "volume": 0.001, "radius": 0.05}]})");
    ASSERT_TRUE(s.terrain.has_value());
    Tin tin = make_script_terrain(*s.terrain);
    for (VertexId v : test::live_ids(tin))
        ASSERT_DOUBLE_EQ(tin.vertices().bedrock[v.index()], 0.08);
    const double before = tin.volume();
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const VertexArrays& va = tin.vertices();
    const auto lowest = [&] {
        double z = 1e300;
        for (VertexId v : test::live_ids(tin)) {
            EXPECT_GE(va.height[v.index()], va.bedrock[v.index()]);
            EXPECT_LE(va.bedrock[v.index()], 0.08);
            z = std::min(z, va.height[v.index()]);
        }
        return z;
    };
    EXPECT_NEAR(lowest(), 0.08, 1e-9) << "the removal dug down to the bedrock";
    // 0.001 m3 is more than the 0.02 m of sand under the dab: less came out, and it says so.
    const double removed = before - tin.volume();
    EXPECT_GT(removed, 1e-5);
    EXPECT_LT(removed, 0.001);
    EXPECT_NEAR(reports.at(0).at("volume_change").get<double>(), -removed, 1e-12);
    // The pit's walls slide in, and the sand still never goes below the bedrock.
    run_script(parse(R"([{"op": "erode", "until_rest": true}])"), tin, context);
    EXPECT_GE(lowest(), 0.08);
    // Without sand_depth there is no bedrock (the default), and a negative depth is an error.
    EXPECT_THROW(parse(R"({"version": 1, "terrain": {"sand_depth": -1}, "operations": []})"),
                 JsonInputError);
}

TEST(Script, AnErodeThatProjectsFirstTurnsAPourIntoTheAnalyticCone) {
    // 4 litres poured in one dab, projected, then relaxed to rest: the analytic cone
    // (physics/cone.hpp) up to the mesh (6 000 random points: measured 0.47 % of its height),
    // no face steeper than repose, and the volume exact.
    const double volume = 0.004;
    const Script s = parse(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 6000, "seed": 3, "sand_depth": 0.05},
        "operations": [{"op": "pour", "at": [0.5, 0.5], "volume": 0.004, "radius": 0.02},
                       {"op": "erode", "until_rest": true, "relocation_radius": 0.01,
                        "project": true}]})");
    const ErodeOp& op = std::get<ErodeOp>(s.steps.at(1).operation);
    ASSERT_TRUE(op.project);
    // The relaxation after a projection has no settle margin, unless the op gives one.
    ASSERT_TRUE(op.settings.has_value());
    EXPECT_EQ(op.settings->parameters.settle_margin, 0.0);
    const Script given =
        parse(R"([{"op": "erode", "until_rest": true, "project": true, "settle_margin": 0.05}])");
    EXPECT_EQ(std::get<ErodeOp>(given.steps.at(0).operation).settings->parameters.settle_margin,
              0.05);
    EXPECT_FALSE(
        std::get<ErodeOp>(parse(R"([{"op": "erode", "iterations": 3}])").steps.at(0).operation)
            .project);
    Tin tin = make_script_terrain(*s.terrain);
    const double before = tin.volume();
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const nlohmann::json& erode = reports.at(1);
    EXPECT_TRUE(erode.at("at_rest").get<bool>());
    EXPECT_TRUE(erode.at("projection").at("converged").get<bool>());
    EXPECT_GT(erode.at("projection").at("moved_vertices").get<std::size_t>(), 100u);
    // Projected where the pour left the sand out of repose, not over the whole terrain: the
    // cone covers a tenth of it (R = 0.18 m).
    EXPECT_GT(erode.at("projection").at("steep_faces").get<std::size_t>(), 0u);
    EXPECT_GE(erode.at("projection").at("rounds").get<int>(), 1);
    EXPECT_LT(erode.at("projection").at("free_vertices").get<std::size_t>(), tin.vertex_count() / 2)
        << erode.at("projection");
    EXPECT_NEAR(tin.volume(), before + volume, 1e-12);
    FaceSlopeOptions judge;
    judge.tolerance = 1e-3;
    EXPECT_LE(measure_face_slopes(tin, MaterialTable::presets(), judge).max_ratio, 1.0 + 1e-3);
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    const Cone cone = Cone::from_volume(volume, tan_alpha);
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < 200; ++i) {
        for (int j = 0; j < 200; ++j) {
            const Vec2 p{0.2 + 0.6 * (i + 0.5) / 200, 0.2 + 0.6 * (j + 0.5) / 200};
            const double r = length(p - Vec2{0.5, 0.5});
            if (r > 1.2 * cone.radius) continue;
            sum += std::abs(*tin.height_at(p) - cone.surface(r));
            ++count;
        }
    }
    EXPECT_LT(sum / count, 0.007 * cone.height);
}

TEST(Script, AnErodeThatProjectsCanFitTheRestSurfacesBends) {
    // The pour above on a coarser terrain, projected with one round of vertices on the pile's
    // toe: the op reports them, the volume stays exact, and the fields are checked.
    const Script s = parse(R"({"version": 1,
        "terrain": {"size": [1, 1], "points": 3000, "seed": 3, "sand_depth": 0.05},
        "operations": [{"op": "pour", "at": [0.5, 0.5], "volume": 0.004, "radius": 0.02},
                       {"op": "erode", "until_rest": true, "relocation_radius": 0.01,
                        "project": true, "fit_bends": 1}]})");
    EXPECT_EQ(std::get<ErodeOp>(s.steps.at(1).operation).fit_bends, 1);
    EXPECT_EQ(
        std::get<ErodeOp>(
            parse(R"([{"op": "erode", "iterations": 1, "project": true}])").steps.at(0).operation)
            .fit_bends,
        0);
    EXPECT_THROW(parse(R"([{"op": "erode", "iterations": 1, "fit_bends": 1}])"), JsonInputError);
    EXPECT_THROW(parse(R"([{"op": "erode", "iterations": 1, "project": true, "fit_bends": -1}])"),
                 JsonInputError);
    EXPECT_THROW(parse(R"([{"op": "erode", "iterations": 1, "project": true, "fit_bends": 9}])"),
                 JsonInputError);
    Tin tin = make_script_terrain(*s.terrain);
    const double before = tin.volume();
    const std::size_t vertices_before = tin.vertex_count();
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const nlohmann::json& projection = reports.at(1).at("projection");
    EXPECT_TRUE(projection.at("converged").get<bool>());
    const auto fitted = projection.at("fitted_vertices").get<std::size_t>();
    EXPECT_GT(fitted, 20u) << projection;
    EXPECT_GE(tin.vertex_count(), vertices_before + fitted);
    EXPECT_NEAR(tin.volume(), before + 0.004, 1e-12);
    EXPECT_TRUE(reports.at(1).at("at_rest").get<bool>());
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

TEST(Script, PaintedMoistSandHoldsTheSlopeItsMoistureGives) {
    const MaterialTable presets = MaterialTable::presets();
    const double tan40 = std::tan(40.0 * std::numbers::pi / 180.0);
    ASSERT_GT(presets.at(1).talus_slope(presets.at(1).default_moisture), tan40 * 1.05);
    ASSERT_LT(presets.at(0).talus_slope(0.0), tan40);
    for (const bool paint : {true, false}) {
        SCOPED_TRACE(paint ? "painted moist" : "left dry");
        Tin tin = ramp_terrain(tan40, 17);
        const std::vector<double> before = tin.vertices().height;
        const std::string painting =
            paint ? R"({"op": "brush", "kind": "paint", "material": 1, "radius": 0.15, "path": )"
                    R"([[0.05, 0.05], [0.05, 0.95], [0.25, 0.95], [0.25, 0.05], [0.45, 0.05],)"
                    R"( [0.45, 0.95], [0.65, 0.95], [0.65, 0.05], [0.85, 0.05], [0.85, 0.95],)"
                    R"( [1, 0.95], [1, 0.05]], "spacing": 0.02},)"
                  : "";
        const Script s = parse("[" + painting + R"({"op": "erode", "until_rest": true}])");
        SculptContext context(tin.domain());
        run_script(s, tin, context);
        const VertexArrays& va = tin.vertices();
        const double moved = largest_change(tin, before);
        std::size_t moist = 0;
        for (VertexId v : test::live_ids(tin)) {
            if (va.material[v.index()] == 1 && va.moisture[v.index()] == 0.25f) ++moist;
        }
        if (paint) {
            EXPECT_EQ(moist, tin.vertex_count()) << "every vertex painted, with its moisture";
            EXPECT_EQ(moved, 0.0);
        } else {
            EXPECT_GT(moved, 0.01);
        }
    }
    // An explicit moisture replaces the material's; a material the scene lacks is an error
    // naming the line and the materials there are.
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 500, 18);
    SculptContext context(tin.domain());
    run_script(parse(R"([{"op": "brush", "kind": "paint", "material": 2, "moisture": 0.6,
                          "at": [0.5, 0.5], "radius": 0.2}])"),
               tin, context);
    const VertexId centre{tin.locate({0.5, 0.5}).corners[0]};
    EXPECT_EQ(tin.vertices().moisture[centre.index()], 0.6f);
    try {
        run_script(parse(R"([{"op": "brush", "kind": "paint", "material": 3, "at": [0.5, 0.5]}])"),
                   tin, context);
        ADD_FAILURE() << "material 3 was painted on a scene of three materials";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("script.json:1"), std::string::npos) << what;
        EXPECT_NE(what.find("material 3: the scene has 3 materials (0 dry_sand, 1 moist_sand, "
                            "2 gravel)"),
                  std::string::npos)
            << what;
    }
    EXPECT_NE(error_of(R"([{"op": "brush", "kind": "raise", "moisture": 0.5, "at": [0, 0]}])")
                  .find("moisture"),
              std::string::npos);
    EXPECT_NE(error_of(R"([{"op": "brush", "kind": "paint", "moisture": 2, "at": [0, 0]}])")
                  .find("moisture"),
              std::string::npos);
}

// A scene from the editor keeps its material table in its metadata, and a script run on it
// erodes with that table: dry sand edited to a 40-degree repose holds a 36-degree slope, which
// the presets (32 degrees) let slide.
TEST(Script, ErodesWithTheMaterialsOfTheSessionItRunsOn) {
    MaterialTable presets = MaterialTable::presets();
    std::vector<Material> edited = presets.all();
    edited[0].repose_dry = 40.0 * std::numbers::pi / 180.0;
    const double tan36 = std::tan(36.0 * std::numbers::pi / 180.0);
    for (const bool with_table : {true, false}) {
        SCOPED_TRACE(with_table ? "the session's table" : "no table: the presets");
        Tin tin = ramp_terrain(tan36, 19);
        const std::vector<double> before = tin.vertices().height;
        Session opened;
        opened.metadata_json =
            with_table ? session_metadata(MaterialTable(edited), R"({"scene": "dunes"})") : "{}";
        SculptContext context(tin.domain());
        run_script(parse(R"([{"op": "erode", "until_rest": true}])"), tin, context, {}, &opened);
        const double moved = largest_change(tin, before);
        if (with_table) {
            EXPECT_EQ(moved, 0.0);
        } else {
            EXPECT_GT(moved, 0.01);
        }
    }
    // A table in the metadata that is not valid is an error naming it.
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 200, 20);
    Session broken;
    broken.metadata_json = R"({"materials": [{"name": "x", "repose_dry_deg": 95}]})";
    SculptContext context(tin.domain());
    EXPECT_THROW(
        run_script(parse(R"([{"op": "erode", "iterations": 1}])"), tin, context, {}, &broken),
        JsonInputError);
}

TEST(Script, ErrorsNameTheLineAndTheField) {
    struct Case {
        const char* what;
        std::string text;
        std::vector<std::string> expected;  ///< substrings of the message
    };
    const std::string ok = R"(  {"op": "pour", "at": [0.5, 0.5], "volume": 1e-5},)";
    const Case cases[] = {
        {"negative radius on line 7",
         "[\n" + ok + "\n" + ok + "\n" + ok + "\n" + ok + "\n" + ok +
             "\n  {\"op\": \"pour\", \"at\": [0.5, 0.5], \"volume\": 1e-5, \"radius\": -0.02}\n]",
         {"script.json:7:", "radius", "positive"}},
        {"negative tool radius",
         "[\n" + ok +
             "\n  {\"op\": \"stamp\", \"tool\": {\"contour\": \"circle\", \"radius\": -1}, "
             "\"at\": [0.5, 0.5]}\n]",
         {"script.json:3:", "tool", "radius"}},
        {"unknown field",
         "[\n" + ok +
             "\n  {\"op\": \"stamp\", \"tool\": {\"asset\": \"circle\"}, \"at\": [0.5, "
             "0.5], \"depht\": 0.01}\n]",
         {"script.json:3:", "depht", "unknown"}},
        {"unknown field of a save",
         "[\n" + ok + "\n  {\"op\": \"save\", \"path\": \"ck.sandtin\", \"formt\": 2}\n]",
         {"script.json:3:", "formt", "unknown"}},
        {"unknown op",
         "[\n  {\"op\": \"dig\", \"at\": [0.5, 0.5]}\n]",
         {"script.json:2:", "op", "dig"}},
        {"invalid JSON",
         "[\n" + ok + "\n" + ok + "\n  {\"op\": \"pour\", \"at\": [0.5, 0.5] \"volume\": 1e-5}\n]",
         {"script.json:4:", "JSON"}},
        {"missing volume",
         "[\n" + ok + "\n  {\"op\": \"pour\", \"at\": [0.5, 0.5]}\n]",
         {"script.json:3:", "volume"}},
        {"depth and bottom",
         "[\n  {\"op\": \"stamp\", \"tool\": {\"asset\": \"circle\"}, \"at\": [0, 0], \"depth\": "
         "0.1, \"bottom\": 0}\n]",
         {"script.json:2:", "depth", "bottom"}},
        {"smooth strength above 1",
         "[\n\n\n  {\"op\": \"brush\", \"kind\": \"smooth\", \"at\": [0, 0], \"strength\": 2}\n]",
         {"script.json:4:", "strength"}},
        {"unknown asset",
         "[\n  {\"op\": \"stamp\", \"tool\": {\"asset\": \"no_such_tool\"}, \"at\": [0, 0]}\n]",
         {"script.json:2:", "asset"}},
        {"bad path point",
         "[\n  {\"op\": \"stroke\", \"tool\": {\"asset\": \"circle\"}, \"path\": [[0, 0], [1]]}\n]",
         {"script.json:2:", "path"}},
        {"unknown top-level field", R"({"operations": [], "bogus": 1})", {"bogus"}},
        {"bad terrain size",
         R"({"terrain": {"size": [0, 1]}, "operations": []})",
         {"terrain", "size"}},
        {"operations not an array", R"({"operations": {"op": "pour"}})", {"operations"}},
        {"operation not an object", "[\n  42\n]", {"script.json:2:", "object"}},
        // 1.41 m / 1e-7 m = 14 million stamps, past the million one operation may place (it
        // used to run for hours); the same for a pour's and a brush's dabs.
        {"stroke spacing too fine",
         "[\n  {\"op\": \"stroke\", \"tool\": {\"asset\": \"circle\"}, \"path\": [[0, 0], [1, "
         "1]], \"spacing\": 1e-7, \"depth\": 0.01}\n]",
         {"script.json:2:", "spacing", "14142135", "1000000"}},
        {"pour spacing too fine",
         "[\n" + ok +
             "\n  {\"op\": \"pour\", \"path\": [[0, 0], [2, 0]], \"volume\": 1e-5, "
             "\"spacing\": 1e-6}\n]",
         {"script.json:3:", "spacing", "2000000"}},
        {"brush spacing too fine",
         "[\n  {\"op\": \"brush\", \"path\": [[0, 0], [0, 1], [1, 1]], \"spacing\": 1e-6}\n]",
         {"script.json:2:", "spacing", "2000000"}},
        // Heights beyond kMaxHeight (1e9 m, the largest terrain side) would make volumes and
        // exported meshes infinite: a depth of 1e300 m once gave a volume of -4.9e297 m^3.
        {"stamp depth beyond 1e9 m",
         "[\n  {\"op\": \"stamp\", \"tool\": {\"asset\": \"circle\"}, \"at\": [0, 0], "
         "\"depth\": 1e300}\n]",
         {"script.json:2:", "depth", "[-1e+09, 1e+09]"}},
        {"stroke bottom beyond 1e9 m",
         "[\n  {\"op\": \"stroke\", \"tool\": {\"asset\": \"circle\"}, \"path\": [[0, 0], [1, "
         "1]], \"bottom\": -2e9}\n]",
         {"script.json:2:", "bottom", "1e+09"}},
        {"flatten height beyond 1e9 m",
         "[\n  {\"op\": \"brush\", \"kind\": \"flatten\", \"at\": [0, 0], \"height\": 1e300}\n]",
         {"script.json:2:", "height"}},
        {"raise strength beyond 1e9 m",
         "[\n  {\"op\": \"brush\", \"kind\": \"raise\", \"at\": [0, 0], \"strength\": 1e300}\n]",
         {"script.json:2:", "strength"}},
        {"pour volume beyond 1e27 m^3",
         "[\n  {\"op\": \"pour\", \"at\": [0, 0], \"volume\": 1e300}\n]",
         {"script.json:2:", "volume", "1e+27"}},
        // Fields another kind of brush (or erode mode) reads would be silently ignored.
        {"height on a raise brush",
         "[\n  {\"op\": \"brush\", \"kind\": \"raise\", \"at\": [0, 0], \"height\": 0.1}\n]",
         {"script.json:2:", "height", "flatten"}},
        {"material on a smooth brush",
         "[\n  {\"op\": \"brush\", \"kind\": \"smooth\", \"at\": [0, 0], \"material\": 1}\n]",
         {"script.json:2:", "material", "paint"}},
        {"strength on a paint brush",
         "[\n  {\"op\": \"brush\", \"kind\": \"paint\", \"at\": [0, 0], \"strength\": 1}\n]",
         {"script.json:2:", "strength", "paint"}},
        {"max_iterations without until_rest",
         "[\n  {\"op\": \"erode\", \"iterations\": 5, \"max_iterations\": 9}\n]",
         {"script.json:2:", "max_iterations", "until_rest"}},
        {"a key given twice",
         "[\n  {\"op\": \"pour\", \"at\": [0.5, 0.5],\n   \"volume\": 1e-5, \"volume\": 1}\n]",
         {"script.json:3:", "'volume'", "twice"}},
        {"terrain height beyond 1e9 m",
         R"({"terrain": {"height": 1e300}, "operations": []})",
         {"terrain", "height"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        const std::string message = error_of(c.text);
        ASSERT_FALSE(message.empty()) << "the script parsed:\n" << c.text;
        for (const std::string& e : c.expected)
            EXPECT_NE(message.find(e), std::string::npos) << "'" << e << "' not in: " << message;
    }
}

// Just inside the limit on placements: a 1 m pour path every 2 um parses into its 500 001
// points (both ends included).
TEST(Script, AFinePathWithinThePlacementLimitParses) {
    const Script script = parse(R"([{"op": "pour", "path": [[0, 0.5], [1, 0.5]], "volume": 1e-5,
                                     "spacing": 2e-6}])");
    ASSERT_EQ(script.steps.size(), 1u);
    const auto& pour = std::get<PourOp>(script.steps[0].operation);
    EXPECT_NEAR(static_cast<double>(pour.points.size()), 500001.0, 1.0);
}

TEST(Script, ExtensionsAddOperations) {
    int runs = 0;
    const ScriptExtension wobble = [&](const std::string& op, const nlohmann::json& object,
                                       const std::string& context) -> std::optional<CustomOp> {
        if (op != "wobble") return std::nullopt;
        JsonFields f(object, context);
        f.get("op");
        const double steps = f.positive("steps", 1.0);
        f.reject_unknown();
        return CustomOp{"wobble", [&runs, steps](Tin&, SculptContext&) {
                            ++runs;
                            return nlohmann::json{{"steps", steps}};
                        }};
    };
    const Script s =
        parse_script("[\n {\"op\": \"wobble\", \"steps\": 3}\n]", "x.json", ".", {wobble});
    ASSERT_EQ(s.steps.size(), 1u);
    Tin tin = Tin::flat_rectangle(Rect::from_size(1, 1));
    SculptContext context;
    const nlohmann::json r = run_script(s, tin, context);
    EXPECT_EQ(runs, 1);
    EXPECT_EQ(r[0]["steps"], 3.0);
    // Its own field errors still name the line.
    try {
        parse_script("[\n\n {\"op\": \"wobble\", \"steps\": -3}\n]", "x.json", ".", {wobble});
        ADD_FAILURE() << "a negative step count parsed";
    } catch (const JsonInputError& e) {
        EXPECT_NE(std::string(e.what()).find("x.json:3:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("steps"), std::string::npos) << e.what();
    }
    // Without the extension the op is unknown.
    EXPECT_THROW(parse("[{\"op\": \"wobble\"}]"), JsonInputError);
}

// Found by fuzzing: a number beyond double's range is valid JSON syntax, but nlohmann throws
// out_of_range for it, which escaped the parser's JsonInputError contract.
TEST(Script, NumberBeyondDoubleRangeIsAClearError) {
    const std::string e = error_of("{\"version\": 1e660000, \"operations\": []}");
    EXPECT_NE(e.find("script.json"), std::string::npos) << e;
    EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;
    // It names its line, also when the number ends the line (the lexer reads one past it).
    for (const char* text : {"[\n {\"op\": \"pour\",\n  \"volume\": 1e400}\n]",
                             "[\n {\"op\": \"pour\",\n  \"volume\": 1e400\n }\n]",
                             "[\n {\"op\": \"pour\",\n  \"volume\": -1e400, \"at\": [0, 0]}]"}) {
        const std::string line = error_of(text);
        EXPECT_NE(line.find("script.json:3: not valid JSON"), std::string::npos) << line;
    }
}

}  // namespace
}  // namespace sandtin
