// Stamps placed where they cannot work as drawn (degenerate and bad placements): a
// tool wholly or partly outside the domain, cut into pieces by its border, covering all of it,
// too small for the terrain or far larger than its profile's detail, a non-finite placement
// and bad tool specs. Each is either refused with an error that names the problem and leaves
// the terrain as it was, or stamps what lies inside the domain and keeps the mesh sound.
// Oracles: snapshots compared field by field, point-in-polygon in extended precision, the
// surface sampled before and after, brute-force volumes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "stamp_helpers.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin {
namespace {

using namespace stamp_test;
using test::inside_by;
using test::live_ids;
using test::mesh_is_sound;
using test::outside_by;
using test::rolling_sand;

// ---- Degenerate and bad placements -------------------------------------------------------

TEST(Stamp, ToolEntirelyOutsideTheDomainChangesNothing) {
    Tin tin = Tin::random_points(test::kUnitSquare, 500, 61, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const test::TinState before = test::capture(tin);
    for (Vec2 c : {Vec2{1.5, 0.5}, Vec2{-0.2, -0.2}, Vec2{0.5, 1.0 + 0.045}}) {
        const StampReport r = stamp(tin, tool, {c, 0.0, 0.0}, context);
        EXPECT_FALSE(r.applied) << c.x << ", " << c.y;
        EXPECT_EQ(r.displaced_volume, 0.0);
    }
    test::expect_snapshots_equal(before.snapshot, tin.snapshot());
}

TEST(Stamp, ToolPartlyOutsideTheDomainKeepsAValidMesh) {
    Tin tin = Tin::random_points(test::kUnitSquare, 2000, 62, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const Tool lambda = Tool::build(load_tool_asset("lambda"));
    const ToolPlacement places[] = {{{0.01, 0.5}, 0.0, 0.05},  {{0.0, 0.0}, 0.3, 0.05},
                                    {{1.0, 0.97}, 1.0, 0.04},  {{0.5, 1.03}, 0.0, 0.05},
                                    {{0.99, 0.02}, 2.0, 0.05}, {{0.5, -0.038}, 0.0, 0.05}};
    for (const ToolPlacement& at : places) {
        for (const Tool* t : {&tool, &lambda}) {
            SCOPED_TRACE(t->spec().name + " at " + std::to_string(at.centre.x) + ", " +
                         std::to_string(at.centre.y));
            const StampReport r = stamp(tin, *t, at, context);
            ASSERT_TRUE(mesh_is_sound(tin));
            EXPECT_EQ(tin.domain(), test::kUnitSquare);
            if (!r.applied) continue;
            // What of I lies in the domain is at the floor.
            const std::vector<Vec2> inner = world(at, t->shape().inner);
            for (VertexId v : live_ids(tin)) {
                const Vec2 p = tin.position(v);
                if (inside_by(p, inner, 1e-9)) {
                    EXPECT_NEAR(tin.height(v), at.bottom, 1e-12);
                }
            }
        }
    }
    EXPECT_NEAR(tin.volume(), test::brute_force_volume(tin), 1e-12);
}

// A tool's rim tolerance is 1 % of its radius: a big tool pressed in less than that must still
// dig (it once changed nothing, because the same tolerance decided whether the stamp acts).
// Oracle: the floor, and the volume as area times depth, since the terrain is flat.
TEST(Stamp, ABigToolPressedInShallowerThanItsRimToleranceStillDigs) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 64, [](Vec2) { return 0.1; });
    SculptContext context(tin.domain());
    const Tool tool = circle_tool(0.3, 48);
    ASSERT_GT(tool.rim_tolerance(), 0.002);  // the premise: deeper than the cut below
    ASSERT_LT(context.settings.simplify.tolerance, 0.002);
    const ToolPlacement at{{0.5, 0.5}, 0.0, 0.1 - 0.002};
    const double volume_before = tin.volume();
    const StampReport r = stamp(tin, tool, at, context);
    ASSERT_TRUE(r.applied);
    ASSERT_TRUE(mesh_is_sound(tin));
    // The surface inside I is the floor (its vertices there were simplified away, so it is
    // sampled between them).
    const std::vector<Vec2> inner = world(at, tool.shape().inner);
    EXPECT_GT(expect_floor_inside(tin, inner, test::kUnitSquare, 2000, at.bottom), 400u);
    // At least the floor's prism went (I's area times 2 mm), at most O's.
    const double inner_area = static_cast<double>(test::signed_area_ld(inner));
    const double outer_area =
        static_cast<double>(test::signed_area_ld(world(at, tool.shape().outer)));
    EXPECT_GT(r.displaced_volume, inner_area * 0.002 * (1.0 - 1e-9));
    EXPECT_LT(r.displaced_volume, outer_area * 0.002);
    EXPECT_NEAR(volume_before - tin.volume(), r.displaced_volume, 1e-12);
}

// A tool larger than the whole terrain (both contours clipped to the domain's border) lowers
// all of it to its floor: the volume goes down by exactly the domain's area times the depth.
TEST(Stamp, AToolCoveringTheWholeDomainLowersAllOfIt) {
    const Rect domain = Rect::from_size(2.0, 1.0);
    for (const double radius : {1.5, 100.0}) {
        SCOPED_TRACE(radius);
        Tin tin = Tin::random_points(domain, 2000, 65, [](Vec2) { return 0.1; });
        SculptContext context(tin.domain());
        const StampReport r = stamp(tin, circle_tool(radius, 64), {{1.0, 0.5}, 0.0, 0.09}, context);
        ASSERT_TRUE(r.applied);
        ASSERT_TRUE(mesh_is_sound(tin));
        for (VertexId v : live_ids(tin))
            EXPECT_NEAR(tin.height(v), 0.09, 1e-12);
        EXPECT_NEAR(tin.volume(), 2.0 * 0.09, 1e-12);
        EXPECT_NEAR(r.displaced_volume, 2.0 * 0.01, 1e-12);
    }
}

TEST(Stamp, AToolTooSmallForTheTerrainIsAnErrorNotAStampThatDigsNothing) {
    // A 5 km terrain merges points 5 mm apart (its snap distance, 1e-6 of its size). A 5 cm
    // tool's contours are 1.25 mm apart: its inner contour would snap onto its rim.
    Tin tin =
        Tin::random_points(Rect::from_size(5000.0, 5000.0), 2000, 66, [](Vec2) { return 0.1; });
    ASSERT_NEAR(tin.snap_distance(), 0.005, 1e-12);
    SculptContext context(tin.domain());
    const test::TinState before = test::capture(tin);
    try {
        stamp(tin, circle_tool(0.05, 12), {{2500.0, 2500.0}, 0.0, 0.08}, context);
        ADD_FAILURE() << "a 5 cm tool stamped a 5 km terrain";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("too small for this terrain"), std::string::npos) << m;
        EXPECT_NE(m.find("radius of at least 0.8 m"), std::string::npos) << m;  // 4 * 5 mm / 2.5 %
    }
    test::expect_snapshots_equal(before.snapshot, tin.snapshot());
    // The radius the message asks for digs: the floor reaches the tool.
    const StampReport r = stamp(tin, circle_tool(0.81, 12), {{2500.0, 2500.0}, 0.0, 0.08}, context);
    ASSERT_TRUE(r.applied);
    EXPECT_GT(r.displaced_volume, 0.5 * 3.14159 * 0.81 * 0.81 * 0.02);
    EXPECT_NEAR(*tin.height_at({2500.0, 2500.0}), 0.08, 1e-9);
}

TEST(Stamp, NonFinitePlacementThrowsAndChangesNothing) {
    Tin tin = Tin::random_points(test::kUnitSquare, 300, 63, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const test::TinState before = test::capture(tin);
    const ToolPlacement bad[] = {{{nan, 0.5}, 0.0, 0.0}, {{0.5, inf}, 0.0, 0.0},
                                 {{0.5, 0.5}, nan, 0.0}, {{0.5, 0.5}, inf, 0.0},
                                 {{0.5, 0.5}, 0.0, nan}, {{0.5, 0.5}, 0.0, -inf}};
    for (const ToolPlacement& at : bad)
        EXPECT_THROW(stamp(tin, tool, at, context), std::invalid_argument);
    test::expect_snapshots_equal(before.snapshot, tin.snapshot());
}

TEST(Stamp, BadToolSpecsAreRejected) {
    ToolSpec s;
    s.radius = -0.01;
    EXPECT_THROW(Tool::build(s), std::invalid_argument);
    s = ToolSpec{};
    s.control_points = 2;
    EXPECT_THROW(Tool::build(s), std::invalid_argument);
    s = ToolSpec{};
    s.contour = ContourKind::Polygon;
    s.polygon = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};  // a bow tie
    EXPECT_THROW(Tool::build(s), std::invalid_argument);
    s = ToolSpec{};
    s.gap = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(Tool::build(s), std::invalid_argument);
    s = ToolSpec{};
    s.profile = ProfileKind::Heightfield;  // no file
    EXPECT_THROW(Tool::build(s), std::invalid_argument);
}

// A curved profile is sampled on a lattice inside I at the profile's detail. A size typed with
// a hundred extra digits (found by the script fuzzer: a 1.1 m by 2.9e105 m rectangle under a
// 0.2 m ball) sampled without end; it is an error that names the problem.
TEST(Stamp, AToolFarLargerThanItsProfilesDetailIsRejected) {
    ToolSpec s;
    s.contour = ContourKind::Rectangle;
    s.width = 1.1;
    s.length = 2.9e105;
    s.profile = ProfileKind::HalfSphere;
    s.sphere_radius = 0.2;
    try {
        (void)Tool::build(s);
        ADD_FAILURE() << "a 2.9e105 m tool with a 0.2 m ball built";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("interior samples"), std::string::npos) << e.what();
    }
    // The same ball under a tool of sensible size builds, with its lattice.
    s.length = 1.5;
    const Tool tool = Tool::build(s);
    EXPECT_GT(tool.interior_samples().local.size(), 100u);
    EXPECT_LE(static_cast<double>(tool.interior_samples().local.size()), Tool::kMaxInteriorSamples);
}

// A non-convex tool whose connecting part lies past the domain's border reaches the terrain
// as separate pieces. Clipped as one polygon (Sutherland-Hodgman), the pieces are joined by
// "bridges" along the border between them; the inner bridge is constrained at the floor's
// height at both ends, and could dig a trench along the border between the arms. It does not:
// O's bridge lies within I's, and its points, at the terrain's height, split it. Oracle: the
// terrain is flat, so between the arms (beyond O's reach from either) it must still be at its
// height, and the arms' floors must be at the tool's bottom.
TEST(Stamp, AToolCutIntoPiecesByTheBorderDigsOnlyItsPieces) {
    ToolSpec spec;
    spec.name = "u";
    spec.contour = ContourKind::Polygon;
    // A U: two arms 4 cm wide, 12 cm apart, joined by a bar at the bottom.
    spec.polygon = {{-0.1, -0.1},  {0.1, -0.1},    {0.1, 0.1},   {0.06, 0.1},
                    {0.06, -0.06}, {-0.06, -0.06}, {-0.06, 0.1}, {-0.1, 0.1}};
    const Tool tool = Tool::build(spec);
    const auto flat = [](Vec2) { return 0.1; };
    for (const int terrain : {0, 1, 2}) {
        SCOPED_TRACE(terrain == 0   ? "a terrain of four corners"
                     : terrain == 1 ? "random points"
                                    : "a grid, with vertices along the border");
        Tin tin = terrain == 0   ? Tin::flat_rectangle(test::kUnitSquare, 0.1)
                  : terrain == 1 ? Tin::random_points(test::kUnitSquare, 3000, 66, flat)
                                 : Tin::regular_grid(test::kUnitSquare, 100, 100, flat);
        SculptContext context(tin.domain());
        // The bar lies below y = 0, past the border; the arms reach 15 cm into the terrain.
        const ToolPlacement at{{0.5, 0.05}, 0.0, 0.05};
        const StampReport r = stamp(tin, tool, at, context);
        ASSERT_TRUE(r.applied);
        ASSERT_TRUE(mesh_is_sound(tin));
        LocateHint hint;
        const double gap = tool.shape().gap;
        // Along the border and a little inside, between the arms' outer contours.
        for (double x = 0.44 + 2.0 * gap; x <= 0.56 - 2.0 * gap; x += 0.001) {
            for (double y : {0.0, 0.001, 0.02}) {
                const std::optional<double> h = tin.height_at({x, y}, &hint);
                ASSERT_TRUE(h.has_value());
                EXPECT_NEAR(*h, 0.1, 1e-12) << "between the arms at " << x << ", " << y;
            }
        }
        // The arms' floors, on the border and inside.
        for (double x : {0.41, 0.42, 0.43, 0.57, 0.58, 0.59}) {
            for (double y : {0.0, 0.05, 0.14}) {
                const std::optional<double> h = tin.height_at({x, y}, &hint);
                ASSERT_TRUE(h.has_value());
                EXPECT_NEAR(*h, 0.05, 1e-12) << "in an arm at " << x << ", " << y;
            }
        }
        // What went: the arms' floors (2 x 4 cm x 15 cm x 5 cm) and at most their walls.
        const double floors = 2.0 * 0.04 * 0.15 * 0.05;
        EXPECT_GT(r.displaced_volume, floors * (1.0 - 1e-9));
        EXPECT_LT(r.displaced_volume, floors * 1.2);
    }
}

// The same on a tilted plane, for the λ with its legs poking in across each side of the
// domain, its junction outside, at a few headings: outside O every grid point stays on the
// plane (re-triangulating a plane cannot bend it), and inside I it is at the floor.
TEST(Stamp, ALambdaCutIntoPiecesByEachSideKeepsThePlaneOutsideItsOuterContour) {
    const test::Plane plane{0.05, -0.03, 0.1};
    const Tool lambda = Tool::build(load_tool_asset("lambda"));
    const double pi = std::numbers::pi;
    for (const double tilt : {0.0, 0.25, -0.3}) {
        const ToolPlacement places[] = {{{0.5, 1.01}, tilt, 0.0},
                                        {{0.4, -0.01}, pi + tilt, 0.0},
                                        {{-0.01, 0.6}, 0.5 * pi + tilt, 0.0},
                                        {{1.01, 0.3}, -0.5 * pi + tilt, 0.0}};
        for (const ToolPlacement& at : places) {
            SCOPED_TRACE("at " + std::to_string(at.centre.x) + ", " + std::to_string(at.centre.y) +
                         " heading " + std::to_string(at.angle));
            for (const bool grid : {false, true}) {
                // A grid has vertices all along the border, where the pieces' clipped contours run.
                SCOPED_TRACE(grid ? "grid" : "random points");
                Tin tin = grid ? Tin::regular_grid(test::kUnitSquare, 100, 100, plane)
                               : Tin::random_points(test::kUnitSquare, 4000, 67, plane);
                SculptContext context(tin.domain());
                ASSERT_TRUE(stamp(tin, lambda, at, context).applied);
                ASSERT_TRUE(mesh_is_sound(tin));
                const std::vector<Vec2> inner = world(at, lambda.shape().inner);
                const std::vector<Vec2> outer = world(at, lambda.shape().outer);
                LocateHint hint;
                std::size_t outside = 0, inside = 0, moved = 0, shallow = 0;
                Rect box;
                for (Vec2 p : outer)
                    box.expand(p);
                box = Rect{{std::max(box.min.x - 0.02, 0.0), std::max(box.min.y - 0.02, 0.0)},
                           {std::min(box.max.x + 0.02, 1.0), std::min(box.max.y + 0.02, 1.0)}};
                for (Vec2 p : test::grid_points(box, 121, 121)) {
                    const double h = *tin.height_at(p, &hint);
                    if (outside_by(p, outer, 1e-6)) {
                        ++outside;
                        if (std::abs(h - plane(p)) > 1e-12) ++moved;
                    } else if (inside_by(p, inner, 1e-9)) {
                        ++inside;
                        if (std::abs(h) > 1e-12) ++shallow;
                    }
                }
                EXPECT_EQ(moved, 0u) << moved << " of " << outside << " points outside O moved";
                EXPECT_EQ(shallow, 0u) << shallow << " of " << inside << " points inside I are "
                                       << "not at the floor";
                EXPECT_GT(inside, 100u);
                EXPECT_GT(outside, 1000u);
            }
        }
    }
}

// An imported elevation model: 400 points over 500 m of hills, each triangle tens of metres wide
// and far from flat. Inserting a tool's rim by Delaunay's rule re-shaped triangles far beyond
// it (4.6 cm, 23 m away, under a 0.5 m tool placed on a vertex of the model); the bent edges
// around the rim are now constrained first (Tin::fence_bent_edges). Oracle: the surface before
// the stamp, sampled on a grid around the tool. Outside O it may move by no more than the rim
// tolerance (the rim follows the terrain that closely, and the wall leans on it); placements in
// a triangle, on a vertex, next to one and on an edge, for a small and a large tool, and for one
// as wide as the model's triangles, whose rim re-shapes edges shorter than itself (2.9 m outside
// O while only edges longer than the tool were fenced).
TEST(Stamp, OnACoarseElevationModelTheSurfaceOutsideOHoldsWithinTheRimTolerance) {
    const Tin model = test::coarse_hills_model();
    const std::vector<Vec2> places = test::coarse_model_placements(model, true);
    for (const double radius : {0.5, 5.0, 20.0}) {
        const Tool tool = circle_tool(radius, 12);
        for (const Vec2 at : places) {
            SCOPED_TRACE(std::to_string(radius) + " m tool at " + std::to_string(at.x) + ", " +
                         std::to_string(at.y));
            Tin tin = Tin::from_snapshot(model.snapshot());
            SculptContext context(tin.domain());
            const StampReport r = stamp(tin, tool, {at, 0.0, *tin.height_at(at) - 0.05}, context);
            ASSERT_TRUE(r.applied);
            ASSERT_TRUE(mesh_is_sound(tin));
            EXPECT_GT(r.edges_fenced, 0u) << "the premise: this model has bent edges to fence";
            const std::vector<Vec2> outer = world({at, 0.0, 0.0}, tool.shape().outer);
            double worst = 0.0;
            Vec2 worst_at;
            std::size_t compared = 0;
            LocateHint before_hint, after_hint;
            // Far enough out for the reach the unfenced edges had (up to three radii beyond O).
            const double reach = 60.0 + 3.0 * radius;
            for (Vec2 p : test::grid_points(Rect{at - Vec2{reach, reach}, at + Vec2{reach, reach}},
                                            241, 241)) {
                if (!model.domain().contains(p) || !outside_by(p, outer, 1e-3)) continue;
                ++compared;
                const double d =
                    std::abs(*tin.height_at(p, &after_hint) - *model.height_at(p, &before_hint));
                if (d > worst) worst_at = p;
                worst = std::max(worst, d);
            }
            EXPECT_GT(compared, 50000u);
            EXPECT_LE(worst, tool.rim_tolerance())
                << "the surface moved outside O by " << worst << " m at " << worst_at.x << ", "
                << worst_at.y << ", " << distance(worst_at, at) << " m from the tool";
        }
    }
}

}  // namespace
}  // namespace sandtin
