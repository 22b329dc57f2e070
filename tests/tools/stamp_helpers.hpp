#pragma once
// What the stamp tests share: a circular tool of a given radius, a tool's local contour placed
// in the world, and the check that a stamp's floor is level inside its inner contour.

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <vector>

#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin::stamp_test {

/// A circular tool (ContourKind::Circle) of `radius` metres.
inline Tool circle_tool(double radius, int control_points = 12) {
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = radius;
    spec.control_points = control_points;
    return Tool::build(spec);
}

inline std::vector<Vec2> world(const ToolPlacement& at, std::span<const Vec2> local) {
    return test::rotate_all(local, at.centre, at.angle);
}

/// Samples the surface at `count` random points of `box` (seeded) and expects the floor height
/// `bottom` at those inside `inner` (by 1e-9 m); returns how many were inside.
inline std::size_t expect_floor_inside(const Tin& tin, std::span<const Vec2> inner, const Rect& box,
                                       std::size_t count, double bottom) {
    std::size_t sampled = 0;
    LocateHint hint;
    for (Vec2 p : test::random_points_in(box, count, 1)) {
        if (!test::inside_by(p, inner, 1e-9)) continue;
        ++sampled;
        const std::optional<double> h = tin.height_at(p, &hint);
        EXPECT_TRUE(h.has_value()) << "at " << p.x << ", " << p.y;
        if (h) {
            EXPECT_NEAR(*h, bottom, 1e-12) << "at " << p.x << ", " << p.y;
        }
    }
    return sampled;
}

}  // namespace sandtin::stamp_test
