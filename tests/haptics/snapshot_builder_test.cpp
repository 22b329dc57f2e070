// Snapshots from the TIN: control points on the tool's outer contour, heights interpolated
// from the terrain (checked against a plane, where interpolation is exact), and the material
// under the tool.

#include <gtest/gtest.h>

#include "haptics/snapshot_builder.hpp"
#include "tools/tool.hpp"

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

TEST(SnapshotBuilder, MaterialUnderTheToolAndClampingAtTheBorder) {
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
    for (std::uint32_t i = 0; i < s.control_count; ++i) {
        EXPECT_GE(s.control[i].x, 0.0);  // clamped into the domain
        EXPECT_EQ(s.control_height[i], 0.0);
    }
}

}  // namespace
}  // namespace sandtin::haptics
