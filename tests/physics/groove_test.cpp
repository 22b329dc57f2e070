// The seeds' groove (a circular tool of radius 4 cm dragged 10 cm deep along the diagonal of a
// random 10⁴-point terrain) collapses until its walls lie at the angle of repose; and the
// `erode` script op and the stroke flag drive the same physics.

#include <gtest/gtest.h>

#include "io/script.hpp"
#include "physics/sand_physics.hpp"
#include "physics_oracles.hpp"
#include "tools/stroke.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {

TEST(Groove, WallsCollapseToRepose) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 10000, 2009);
    SculptContext context(tin.domain());
    SandPhysics physics(tin, MaterialTable::presets(), {});
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = 0.04;
    spec.control_points = 12;
    const Tool tool = Tool::build(spec);
    StrokeSettings settings;
    settings.spacing = 0.01;
    settings.depth_mode = DepthMode::Absolute;
    settings.depth = -0.1;
    const std::vector<Vec2> path = {{0.1, 0.1}, {0.9, 0.9}};
    apply_stroke(tin, tool, path, settings, context);
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    // Freshly cut, the walls are far steeper than the angle of repose.
    ASSERT_GT(test::steepest_edge_ratio(tin, tan_alpha), 3.0);
    const double before = tin.volume();
    const PhysicsStepReport r = physics.run_to_rest(200000);
    EXPECT_TRUE(r.at_rest);
    EXPECT_NEAR(tin.volume(), before, 1e-12);
    const double steepest = test::steepest_edge_ratio(tin, tan_alpha);
    EXPECT_LE(steepest, 1.0 + 1e-3);
    EXPECT_GE(steepest, 0.99);  // the walls stop at alpha, they do not flatten further
    // Still a groove: the middle of the trace lies well below the untouched ground.
    EXPECT_LT(*tin.height_at({0.5, 0.5}), -0.02);
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(ErodeScript, OpAndStrokeFlagRelaxToRest) {
    const std::string text = R"({
      "terrain": {"size": [1, 1], "points": 3000, "seed": 3},
      "operations": [
        {"op": "stroke", "tool": {"contour": "circle", "radius": 0.05}, "depth": 0.05,
         "path": [[0.2, 0.5], [0.8, 0.5]], "erode": true, "erode_iterations": 5},
        {"op": "erode", "until_rest": true, "schedule": "jacobi", "threads": 2}
      ]})";
    const Script script = parse_script(text, "erode-test", ".");
    ASSERT_TRUE(script.uses_physics);
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 3);
    SculptContext context(tin.domain());
    ScriptRunner runner(script, tin, context);
    const double before = tin.volume();
    const nlohmann::json stroke = runner.run(script.steps[0]);
    EXPECT_GT(stroke.value("erosion_iterations", 0), 0);
    const double after_stroke = tin.volume();
    const nlohmann::json erode = runner.run(script.steps[1]);
    EXPECT_TRUE(erode.at("at_rest").get<bool>());
    EXPECT_GT(erode.at("vertex_updates").get<std::size_t>(), 0u);
    EXPECT_NEAR(tin.volume(), after_stroke, 1e-12);
    (void)before;
    // The runner simplifies what the erosion touched after it, and removing a vertex
    // re-triangulates its hole, which can leave an edge a little steeper than alpha (measured:
    // 9 %) until the next erosion step; so the bound here is looser than the physics' own.
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    EXPECT_LE(test::steepest_edge_ratio(tin, tan_alpha), 1.15);
    // Bad input names the problem.
    EXPECT_THROW(parse_script(R"({"operations": [{"op": "erode"}]})", "bad", "."), JsonInputError);
    EXPECT_THROW(
        parse_script(R"({"operations": [{"op": "erode", "iterations": 5, "schedule": "magic"}]})",
                     "bad", "."),
        JsonInputError);
}

}  // namespace
}  // namespace sandtin
