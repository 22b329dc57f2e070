// Snapshots from the TIN: control points on the tool's outer contour, heights interpolated
// from the terrain (checked against a plane, where interpolation is exact), and the material
// under the tool; off the terrain, nothing to touch.

#include <gtest/gtest.h>

#include "haptics/force_model.hpp"
#include "haptics/live_editor.hpp"
#include "haptics/snapshot_builder.hpp"
#include "test_support.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::haptics {
namespace {

TEST(SnapshotBuilder, ControlRingAndHeightsOnAPlane) {
    // z = 0.1 + 0.2 x - 0.05 y is reproduced exactly by any triangulation of its samples.
    const auto plane = [](Vec2 p) { return 0.1 + 0.2 * p.x - 0.05 * p.y; };
    const Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 20, 20, plane);
    ToolSpec spec;
    spec.radius = 0.05;
    spec.control_points = 12;
    const Tool tool = Tool::build(spec);
    const ToolPlacement at{{0.42, 0.37}, 0.3, 0.0};
    const HapticSnapshot s = build_snapshot(tin, tool, at, MaterialTable::presets());
    EXPECT_EQ(s.control_count, std::min<std::size_t>(tool.shape().outer.size(), 64));
    EXPECT_EQ(s.centre, at.centre);
    EXPECT_NEAR(s.centre_height, plane(at.centre), 1e-12);
    for (std::uint32_t i = 0; i < s.control_count; ++i) {
        EXPECT_NEAR(s.control_height[i], plane(s.control[i]), 1e-12);
        // On the outer contour: just outside the inner radius.
        const double r = distance(s.control[i], at.centre);
        EXPECT_GT(r, 0.05 * 0.9);
        EXPECT_LT(r, 0.05 * 1.1);
    }
    EXPECT_EQ(s.stiffness, MaterialTable::presets().at(0).haptic_stiffness);
}

TEST(SnapshotBuilder, MaterialUnderTheToolAndPointsOffTheTerrainAtTheBorder) {
    Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 10, 10);
    for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v) {
        if (tin.is_alive(VertexId(v))) tin.set_material(VertexId(v), 2);
    }
    const MaterialTable materials = MaterialTable::presets();
    ASSERT_GE(materials.size(), 3u);
    const Tool tool = Tool::build(ToolSpec{});
    const HapticSnapshot s = build_snapshot(tin, tool, {{0.0, 0.5}, 0.0, 0.0}, materials);
    EXPECT_EQ(s.stiffness, materials.at(2).haptic_stiffness);
    EXPECT_EQ(s.friction, materials.at(2).haptic_friction);
    EXPECT_EQ(s.terrain, tin.domain());
    EXPECT_EQ(s.centre, (Vec2{0.0, 0.5}));
    std::size_t off = 0;
    for (std::uint32_t i = 0; i < s.control_count; ++i) {
        // Where the tool is, not clamped into the domain; the height of the nearest terrain.
        if (s.control[i].x < 0.0) ++off;
        EXPECT_EQ(s.control_height[i], 0.0);
    }
    EXPECT_GT(off, 0u);
}

// A 2 x 1 m terrain of flat sand at z = 0 (the audit's scene), the default dry sand.
struct FlatSand {
    Tin tin = Tin::regular_grid(Rect::from_size(2.0, 1.0), 40, 20, [](Vec2) { return 0.0; });
    SculptContext context{tin.domain()};
    LiveEditor editor{tin,
                      std::make_shared<const Tool>(
                          Tool::build(parse_tool_spec(test::circle_tool_json(), ".", "tool"))),
                      context,
                      {}};
    // The force the loop would render with the tool at the device point (at rest).
    ForceSample probe(Vec3 p) {
        editor.apply({0, p, 0});
        HapticSnapshot s = editor.snapshot();
        s.sequence = 1;  // as published
        return evaluate_force(s, p, {}, ForceModelParams{});
    }
};

TEST(SnapshotBuilder, AProbeOffTheTerrainTouchesNothing) {
    FlatSand sand;
    const double k = MaterialTable::presets().at(0).haptic_stiffness;
    const double delta = ForceModelParams{}.contact_offset;
    // Control: inside, 1 mm deep, k (1 mm + δ) straight up (1.3 N on dry sand).
    const ForceSample inside = sand.probe({1.0, 0.5, -0.001});
    EXPECT_TRUE(inside.contact);
    EXPECT_NEAR(inside.force.z, k * (0.001 + delta), 1e-9);
    // 5 m and 48 m past the border x = 2, past a corner, and deep below: nothing there.
    for (const Vec3& p : {Vec3{7.0, 0.5, -0.001}, Vec3{50.0, 0.5, -0.001}, Vec3{-1.0, -1.0, -0.001},
                          Vec3{7.0, 0.5, -0.2}, Vec3{1e6, -1e6, -1e6}, Vec3{0.5, -5.0, -0.001}}) {
        const ForceSample f = sand.probe(p);
        EXPECT_FALSE(f.contact) << p.x << " " << p.y << " " << p.z;
        EXPECT_EQ(f.force, (Vec3{})) << p.x << " " << p.y << " " << p.z;
    }
}

TEST(SnapshotBuilder, AProbeOverTheBorderFeelsOnlyThePartOverTheTerrain) {
    FlatSand sand;
    const double depth = 0.003;
    const ForceSample inside = sand.probe({1.0, 0.5, -depth});
    ASSERT_TRUE(inside.contact);
    // The centre 1 mm past the border x = 2: no penetration under it; only the control points
    // over the terrain (x <= 2) push back, each along -u_i with m = depth + δ, the sum divided
    // by all N points (force_model.hpp, rule 2).
    const Vec2 centre{2.001, 0.5};
    const ForceSample f = sand.probe({centre.x, centre.y, -depth});
    const HapticSnapshot s = sand.editor.snapshot();
    ASSERT_EQ(s.centre, centre);
    const Material dry = MaterialTable::presets().at(0);
    const double m = depth + ForceModelParams{}.contact_offset;
    Vec2 expected;
    std::size_t over = 0;
    for (std::uint32_t i = 0; i < s.control_count; ++i) {
        const Vec2 c = s.control[i];
        EXPECT_NEAR(distance(c, centre), 0.04, 0.004);  // on the tool's outer contour
        if (c.x > 2.0) continue;
        ++over;
        expected -= (c - centre) / distance(c, centre) * m;
    }
    expected = expected *
               (dry.haptic_friction * dry.haptic_stiffness / static_cast<double>(s.control_count));
    ASSERT_GT(over, 0u);
    ASSERT_LT(over, s.control_count);
    EXPECT_TRUE(f.contact);
    EXPECT_NEAR(f.force.x, expected.x, 1e-9);
    EXPECT_NEAR(f.force.y, expected.y, 1e-9);
    EXPECT_EQ(f.force.z, 0.0);
    EXPECT_GT(f.force.x, 0.0);  // the sand at the edge pushes the tool back out, towards +x
    EXPECT_LE(length(f.force), length(inside.force));
}

}  // namespace
}  // namespace sandtin::haptics
