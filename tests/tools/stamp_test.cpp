// Stamps: the acceptance criteria of the tool model (flat floor inside I, surface unchanged
// outside O, rim on the pre-stamp terrain, non-convex λ) and generations (bad placements:
// stamp_placement_test.cpp).
// Oracles: the tool's contours transformed to the world by hand, point-in-polygon and distances
// in extended precision over every vertex, the surface sampled before and after the stamp,
// snapshots compared field by field.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "geom/polygon.hpp"
#include "stamp_helpers.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"

namespace sandtin {
namespace {

using namespace stamp_test;
using test::densify;
using test::distance_to_border;
using test::inside_by;
using test::inside_polygon;
using test::live_ids;
using test::mesh_is_sound;
using test::outside_by;
using test::rolling_sand;
using test::surface_at;

// ---- 1. The floor of a flat stamp ---------------------------------------------------------

TEST(Stamp, FlatDigPutsEveryVertexInsideInnerContourAtToolDepth) {
    Tin tin = Tin::random_points(test::kUnitSquare, 4000, 11, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const ToolPlacement at{{0.43, 0.57}, 0.3, 0.05};  // the terrain is >= 0.08 m everywhere
    const std::vector<Vec2> inner = world(at, tool.shape().inner);
    std::size_t covered_before = 0;
    for (VertexId v : live_ids(tin))
        covered_before += inside_polygon(tin.position(v), inner) ? 1 : 0;
    ASSERT_GE(covered_before, 5u) << "the terrain should have vertices under the tool";

    const StampReport r = stamp(tin, tool, at, context);
    ASSERT_TRUE(r.applied);
    EXPECT_TRUE(mesh_is_sound(tin));

    // Every vertex inside I or on it (closed polygon) sits exactly at the tool's bottom.
    std::size_t checked = 0;
    for (VertexId v : live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if (!inside_polygon(p, inner) && distance_to_border(p, inner) > 1e-12) continue;
        EXPECT_NEAR(tin.height(v), at.bottom, 1e-12) << "vertex at " << p.x << ", " << p.y;
        ++checked;
    }
    EXPECT_GE(checked, inner.size());
    // The surface inside I is the floor.
    EXPECT_GT(expect_floor_inside(tin, inner, Rect{{0.38, 0.52}, {0.48, 0.62}}, 4000, at.bottom),
              1000u);
    // The volume it took: at least the prism between the lowest terrain and the floor, at most
    // the one from the highest (inner polygon area times the depth range).
    const double area = static_cast<double>(test::signed_area_ld(inner));
    EXPECT_GT(r.displaced_volume, area * (0.08 - at.bottom) * 0.99);
    EXPECT_LT(r.displaced_volume,
              static_cast<double>(test::signed_area_ld(world(at, tool.shape().outer))) *
                  (0.13 - at.bottom));
}

TEST(Stamp, RepeatingAStampChangesNothing) {
    // The terrain already holds the imprint: the second stamp must not add vertices,
    // constraints or volume changes (re-working a trail would otherwise grow the mesh forever).
    // And a stamp that is not a repeat, a little deeper, still acts.
    Tin tin = Tin::random_points(test::kUnitSquare, 4000, 12, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const ToolPlacement at{{0.52, 0.47}, 0.2, 0.06};
    ASSERT_TRUE(stamp(tin, tool, at, context).applied);
    const std::size_t vertices = tin.vertex_count();
    const std::size_t constraints = tin.constraint_count();
    const std::vector<double> heights = tin.vertices().height;
    const double volume = tin.volume();

    const StampReport again = stamp(tin, tool, at, context);
    EXPECT_TRUE(again.applied);
    EXPECT_EQ(again.vertices_inserted, 0u);
    EXPECT_EQ(again.triangles_touched, 0u);
    EXPECT_EQ(again.volume_change, 0.0);
    EXPECT_EQ(tin.vertex_count(), vertices);
    EXPECT_EQ(tin.constraint_count(), constraints);
    EXPECT_EQ(tin.vertices().height, heights);
    EXPECT_EQ(tin.volume(), volume);

    const ToolPlacement deeper{at.centre, at.angle, at.bottom - 0.005};
    const StampReport dug = stamp(tin, tool, deeper, context);
    EXPECT_GT(dug.displaced_volume, 0.0);
    EXPECT_LT(tin.volume(), volume);
    EXPECT_TRUE(mesh_is_sound(tin));
}

TEST(Stamp, LevelModeSetsTheFootprintExactlyEvenAboveTheTerrain) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 12, rolling_sand);
    SculptContext context(tin.domain());
    ToolSpec spec = load_tool_asset("circle");
    spec.mode = ImprintMode::Level;
    const Tool tool = Tool::build(spec);
    const ToolPlacement at{{0.6, 0.35}, 0.0, 0.15};  // above the terrain (<= 0.13 m)
    const double before = tin.volume();
    ASSERT_TRUE(stamp(tin, tool, at, context).applied);
    EXPECT_TRUE(mesh_is_sound(tin));
    const std::vector<Vec2> inner = world(at, tool.shape().inner);
    std::size_t checked = 0;
    for (VertexId v : live_ids(tin)) {
        if (!inside_polygon(tin.position(v), inner)) continue;
        EXPECT_NEAR(tin.height(v), at.bottom, 1e-12);
        ++checked;
    }
    EXPECT_GE(checked, 3u);
    EXPECT_GT(tin.volume(), before) << "a level tool above the sand fills";
}

// A vertex of the terrain exactly on the inner contour (a grid terrain under a tool at round
// coordinates: on its edges and at its corners) is part of the footprint too. In level mode it
// kept its height, and its triangles left a wedge 12.5 mm off the level inside the footprint.
// Oracle: the level, at every vertex on or inside I and at samples inside I.
TEST(Stamp, LevelModeLevelsVerticesLyingExactlyOnTheInnerContour) {
    std::vector<Vec2> grid;
    std::vector<double> heights;
    for (int i = 0; i <= 100; ++i) {
        for (int j = 0; j <= 100; ++j) {
            grid.push_back({0.01 * i, 0.01 * j});
            heights.push_back(rolling_sand(grid.back()));
        }
    }
    for (const ImprintMode mode : {ImprintMode::Level, ImprintMode::Dig}) {
        SCOPED_TRACE(mode == ImprintMode::Level ? "level" : "dig");
        Tin tin = Tin::from_points(test::kUnitSquare, grid, heights);
        SculptContext context(tin.domain());
        ToolSpec spec;
        spec.contour = ContourKind::Rectangle;
        spec.length = 0.1;
        spec.width = 0.06;
        spec.mode = mode;
        const Tool tool = Tool::build(spec);
        const Vec2 centre{0.3, 0.6};
        const double level = *tin.height_at(centre) - 0.02;
        const ToolPlacement at{centre, 0.0, level};
        const std::vector<Vec2> inner = world(at, tool.shape().inner);
        std::size_t on_contour = 0;
        for (VertexId v : live_ids(tin)) {
            if (nearest_edge(tin.position(v), inner).distance < 1e-12) ++on_contour;
        }
        ASSERT_GE(on_contour, 6u) << "the premise: grid vertices lie on I's edges";
        ASSERT_TRUE(stamp(tin, tool, at, context).applied);
        ASSERT_TRUE(mesh_is_sound(tin));
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            if (inside_polygon(p, inner) || nearest_edge(p, inner).distance < 1e-12) {
                if (mode == ImprintMode::Level) {
                    EXPECT_NEAR(tin.height(v), level, 1e-12) << p.x << ", " << p.y;
                } else {
                    EXPECT_LE(tin.height(v), level + 1e-12) << p.x << ", " << p.y;
                }
            }
        }
        LocateHint hint;
        for (Vec2 p : test::grid_points(Rect{centre - Vec2{0.05, 0.03}, centre + Vec2{0.05, 0.03}},
                                        61, 41)) {
            if (!inside_by(p, inner, 1e-4)) continue;
            if (mode == ImprintMode::Level) {
                EXPECT_NEAR(*tin.height_at(p, &hint), level, 1e-12) << p.x << ", " << p.y;
            } else {
                EXPECT_LE(*tin.height_at(p, &hint), level + 1e-12) << p.x << ", " << p.y;
            }
        }
    }
}

// A wide tool pressed into a hilltop cuts only inside I: the sand at I and O lies below it.
// It enforced no contour, so the triangles from the lowered cap reached past O and tilted the
// surface there (1.9 mm, 7.7 cm beyond O), it cut the untouched sand between the contours
// down to the rim's height (2 mm, below the tool), and it reported no triangle touched.
// Oracles: the hill before the stamp everywhere outside I, within the rim tolerance (2.2 mm
// against 2 mm before); the cap inside I at the tool.
TEST(Stamp, AToolCuttingOnlyInsideItsInnerContourKeepsItsFootprint) {
    const Vec2 top{0.5, 0.5};
    auto hill = [&](Vec2 p) { return 0.08 - 0.5 * length_squared(p - top); };
    Tin tin = Tin::random_points(test::kUnitSquare, 20000, 31, hill);
    const Tin before = Tin::from_snapshot(tin.snapshot());
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;  // heights exactly as imprinted
    const Tool tool = circle_tool(0.2, 12);
    const ToolPlacement at{top, 0.0, 0.07};  // the cap above 7 cm: 14 cm across, inside I
    const std::vector<Vec2> inner = world(at, tool.shape().inner);
    const std::vector<Vec2> outer = world(at, tool.shape().outer);
    const StampReport r = stamp(tin, tool, at, context);
    ASSERT_TRUE(r.applied);
    ASSERT_TRUE(mesh_is_sound(tin));
    EXPECT_GT(r.triangles_touched, 0u);
    EXPECT_GT(r.displaced_volume, 0.0);
    // Outside I the sand lay below the tool: the surface there keeps its shape, the ramp
    // between the contours following it within the rim tolerance too.
    double worst = 0.0, worst_outside = 0.0;
    LocateHint before_hint, after_hint;
    std::size_t compared = 0;
    for (Vec2 p : test::grid_points(Rect{{0.2, 0.2}, {0.8, 0.8}}, 241, 241)) {
        if (!outside_by(p, inner, 1e-6)) continue;
        ++compared;
        const double d =
            std::abs(*tin.height_at(p, &after_hint) - *before.height_at(p, &before_hint));
        worst = std::max(worst, d);
        if (outside_by(p, outer, 1e-6)) worst_outside = std::max(worst_outside, d);
    }
    RecordProperty("worst_outside_inner_um", static_cast<int>(worst * 1e6));
    RecordProperty("worst_outside_outer_um", static_cast<int>(worst_outside * 1e6));
    EXPECT_GT(compared, 20000u);
    EXPECT_LE(worst, tool.rim_tolerance());
    for (Vec2 p : test::grid_points(Rect{top - Vec2{0.07, 0.07}, top + Vec2{0.07, 0.07}}, 29, 29)) {
        if (hill(p) > 0.0705) {
            EXPECT_NEAR(*tin.height_at(p, &after_hint), 0.07, 1e-12);
        }
    }
}

TEST(Stamp, DigLowersToTheToolAndNeverRaises) {
    // The floor cuts through a wavy surface: part of the footprint lies below it already.
    Tin tin = Tin::random_points(test::kUnitSquare, 10000, 13, test::wavy_sand);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;  // heights exactly as imprinted
    const Tool tool = circle_tool(0.06, 16);
    ToolPlacement at{{0.5, 0.5}, 0.0, 0.0};
    const std::vector<Vec2> inner = world(at, tool.shape().inner);
    // The floor at the median of the analytic surface under the tool.
    std::vector<double> under;
    for (Vec2 p : test::random_points_in(Rect{{0.44, 0.44}, {0.56, 0.56}}, 2000, 2)) {
        if (inside_polygon(p, inner)) under.push_back(test::wavy_sand(p));
    }
    std::nth_element(under.begin(), under.begin() + static_cast<std::ptrdiff_t>(under.size() / 2),
                     under.end());
    at.bottom = under[under.size() / 2];
    const Tin before = Tin::from_snapshot(tin.snapshot());
    ASSERT_TRUE(stamp(tin, tool, at, context).applied);
    EXPECT_TRUE(mesh_is_sound(tin));
    std::size_t lowered = 0, kept = 0, fresh = 0;
    LocateHint hint;
    for (VertexId v : live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if (!inside_polygon(p, inner) && distance_to_border(p, inner) > 1e-12) continue;
        const double h = tin.height(v);
        EXPECT_LE(h, at.bottom + 1e-12);
        EXPECT_LE(h, *before.height_at(p, &hint) + 1e-12) << "dig raised the sand";
        if (v.index() < before.vertex_capacity() && before.is_alive(v) && before.position(v) == p) {
            EXPECT_EQ(h, std::min(before.height(v), at.bottom));
            (before.height(v) > at.bottom ? lowered : kept) += 1;
        } else {
            ++fresh;
        }
    }
    EXPECT_GT(lowered, 20u);
    EXPECT_GT(kept, 20u) << "the test needs terrain below the floor too";
    EXPECT_GT(fresh, 0u) << "the inner contour's points (where it cuts)";
}

// ---- 2. Outside O nothing changes ----------------------------------------------------------
//
// A stamp inserts the points of O on the surface and constrains O. The triangulation stays
// constrained Delaunay, so pre-stamp triangles whose circumcircle contains a new point, or
// which O crosses, are re-triangulated; on a curved surface that bends the surface inside them
// slightly, outside O too (the seeds' method does the same, and no Delaunay triangulation can
// avoid it). Three oracles, from the strictest to the loosest:
//  - a sample outside O in a pre-stamp triangle whose circumdisk misses O (nothing can have
//    re-triangulated it) keeps its height within 1e-9;
//  - a sample in a re-triangulated triangle is a convex combination of its new triangle's
//    corners, which lie on the pre-stamp surface: it stays within their pre-stamp heights;
//  - and it moves by at most the rim tolerance (the fidelity the tool promises along O).

struct Circumdisk {
    Vec2 centre;
    double radius = 0.0;
};

Circumdisk circumdisk(Vec2 a, Vec2 b, Vec2 c) {
    using test::ld;
    const long double d = 2.0L * test::orient2(a, b, c);
    const long double a2 = ld(a.x) * a.x + ld(a.y) * a.y;
    const long double b2 = ld(b.x) * b.x + ld(b.y) * b.y;
    const long double c2 = ld(c.x) * c.x + ld(c.y) * c.y;
    const long double ux = (a2 * (ld(b.y) - c.y) + b2 * (ld(c.y) - a.y) + c2 * (ld(a.y) - b.y)) / d;
    const long double uy = (a2 * (ld(c.x) - b.x) + b2 * (ld(a.x) - c.x) + c2 * (ld(b.x) - a.x)) / d;
    const Vec2 u{static_cast<double>(ux), static_cast<double>(uy)};
    return {u, distance(u, a)};
}

/// For each sample point: may the stamp re-triangulate the pre-stamp triangle under it?
std::vector<std::uint8_t> may_change(const Tin& tin, const std::vector<Vec2>& samples,
                                     std::span<const Vec2> outer) {
    std::vector<std::uint8_t> out(samples.size(), 1);
    LocateHint hint;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Location loc = tin.locate(samples[i], &hint);
        // A point on an edge or a vertex belongs to several triangles: count it as touched.
        if (loc.kind != Location::Kind::InTriangle) continue;
        const auto& t = loc.corners;
        const Vec2 a = tin.position(t[0]), b = tin.position(t[1]), c = tin.position(t[2]);
        // The located triangle really contains the point (checked, not assumed).
        const auto w = test::barycentric(samples[i], a, b, c);
        EXPECT_TRUE(w[0] >= -1e-12L && w[1] >= -1e-12L && w[2] >= -1e-12L);
        const Circumdisk d = circumdisk(a, b, c);
        const bool meets = inside_polygon(d.centre, outer) ||
                           distance_to_border(d.centre, outer) <= d.radius * (1.0 + 1e-9);
        out[i] = meets ? 1 : 0;
    }
    return out;
}

struct OutsideChange {
    std::size_t compared = 0;      ///< samples outside O by the margin
    std::size_t in_untouched = 0;  ///< ... in triangles the stamp had no reason to touch
    std::size_t untouched_moved = 0;
    double worst_untouched = 0.0;       ///< m
    std::size_t out_of_hull = 0;        ///< re-triangulated samples outside their corners' range
    double worst_retriangulated = 0.0;  ///< m
    Vec2 worst_at;
};

OutsideChange outside_change(Tin& tin, const Tool& tool, const ToolPlacement& at,
                             SculptContext& context, double reach) {
    const std::vector<Vec2> outer = world(at, tool.shape().outer);
    const Rect around{{at.centre.x - reach, at.centre.y - reach},
                      {at.centre.x + reach, at.centre.y + reach}};
    std::vector<Vec2> samples;
    const double margin = tool.shape().gap + 1e-4;
    for (Vec2 p : test::grid_points(around, 161, 161)) {
        if (tin.domain().contains(p) && outside_by(p, outer, margin)) samples.push_back(p);
    }
    const std::vector<std::uint8_t> retriangulated = may_change(tin, samples, outer);
    const Tin before = Tin::from_snapshot(tin.snapshot());
    const std::vector<double> h0 = surface_at(before, samples);
    EXPECT_TRUE(stamp(tin, tool, at, context).applied);
    EXPECT_TRUE(mesh_is_sound(tin));
    const std::vector<double> h1 = surface_at(tin, samples);
    OutsideChange c;
    c.compared = samples.size();
    LocateHint hint, old_hint;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const double d = std::abs(h1[i] - h0[i]);
        if (!retriangulated[i]) {
            ++c.in_untouched;
            if (!(d <= 1e-9)) {
                ++c.untouched_moved;
                if (d > c.worst_untouched) c.worst_at = samples[i];
                c.worst_untouched = std::max(c.worst_untouched, d);
            }
            continue;
        }
        if (d > c.worst_retriangulated && c.untouched_moved == 0) c.worst_at = samples[i];
        c.worst_retriangulated = std::max(c.worst_retriangulated, d);
        const Location loc = tin.locate(samples[i], &hint);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (VertexId v : loc.corners) {
            const double z = *before.height_at(tin.position(v), &old_hint);
            lo = std::min(lo, z);
            hi = std::max(hi, z);
        }
        c.out_of_hull += (h1[i] < lo - 1e-12 || h1[i] > hi + 1e-12) ? 1 : 0;
    }
    return c;
}

void expect_unchanged_outside(const OutsideChange& c, const Tool& tool) {
    EXPECT_GT(c.in_untouched, c.compared / 2) << "the samples should mostly lie beyond reach";
    EXPECT_EQ(c.untouched_moved, 0u)
        << "the surface moved outside O, in triangles the stamp had no reason to "
        << "re-triangulate, by up to " << c.worst_untouched << " m (worst at " << c.worst_at.x
        << ", " << c.worst_at.y << ")";
    EXPECT_EQ(c.out_of_hull, 0u) << "re-triangulated surface outside O left the range of the "
                                 << "pre-stamp heights at its corners";
    EXPECT_LE(c.worst_retriangulated, tool.rim_tolerance())
        << "re-triangulation next to O bent the surface by " << c.worst_retriangulated
        << " m (worst at " << c.worst_at.x << ", " << c.worst_at.y << ")";
}

TEST(Stamp, SurfaceOutsideOuterContourIsUnchanged) {
    // A dense, curved terrain; several tools and headings.
    Tin tin = test::smooth_terrain(test::kUnitSquare, 20000, 21, rolling_sand);
    SculptContext context(tin.domain());
    const Tool circle = Tool::build(load_tool_asset("circle"));
    ToolSpec box_spec = load_tool_asset("box");
    box_spec.extrude = false;
    const Tool box = Tool::build(box_spec);
    const Tool lambda = Tool::build(load_tool_asset("lambda"));
    struct Case {
        const Tool* tool;
        ToolPlacement at;
    };
    const Case cases[] = {{&circle, {{0.3, 0.3}, 0.0, 0.05}},
                          {&box, {{0.7, 0.3}, 0.7, 0.06}},
                          {&lambda, {{0.3, 0.7}, -0.4, 0.05}},
                          {&circle, {{0.02, 0.7}, 0.0, 0.05}}};  // across the domain border
    for (const Case& c : cases) {
        SCOPED_TRACE(c.tool->spec().name + " at " + std::to_string(c.at.centre.x) + ", " +
                     std::to_string(c.at.centre.y));
        const OutsideChange change =
            outside_change(tin, *c.tool, c.at, context, c.tool->shape().bounding_radius + 0.05);
        expect_unchanged_outside(change, *c.tool);
    }
}

TEST(Stamp, SurfaceOutsideOuterContourIsExactlyUnchangedOnAPlane) {
    // On a plane re-triangulation cannot bend the surface: outside O nothing may move at all.
    const test::Plane plane{0.05, -0.03, 0.1};
    Tin tin = Tin::random_points(test::kUnitSquare, 10000, 22, plane);
    SculptContext context(tin.domain());
    const Tool lambda = Tool::build(load_tool_asset("lambda"));
    const ToolPlacement at{{0.55, 0.45}, 2.0, 0.0};
    const std::vector<Vec2> outer = world(at, lambda.shape().outer);
    ASSERT_TRUE(stamp(tin, lambda, at, context).applied);
    LocateHint hint;
    std::size_t compared = 0, moved = 0;
    double worst = 0.0;
    Vec2 worst_at;
    for (Vec2 p : test::grid_points(Rect{{0.4, 0.3}, {0.7, 0.6}}, 201, 201)) {
        if (!outside_by(p, outer, lambda.shape().gap + 1e-6)) continue;
        ++compared;
        const double d = std::abs(*tin.height_at(p, &hint) - plane(p));
        if (d > 1e-12) {
            ++moved;
            if (d > worst) worst_at = p;
            worst = std::max(worst, d);
        }
    }
    EXPECT_EQ(moved, 0u) << moved << " of " << compared << " points outside O moved, by up to "
                         << worst << " m (at " << worst_at.x << ", " << worst_at.y << ")";
    // The vertices too: every vertex outside O is still on the plane.
    for (VertexId v : live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if (inside_polygon(p, outer)) continue;
        EXPECT_NEAR(tin.height(v), plane(p), 1e-12)
            << "vertex at " << p.x << ", " << p.y << ", " << distance_to_border(p, outer)
            << " m outside O";
    }
    EXPECT_GT(compared, 30000u);
}

TEST(Stamp, OverlappingStampKeepsTheEarlierImprintOutsideItsOuterContour) {
    // Two flat stamps side by side on flat sand: the second may only change the first crater
    // inside its own O.
    Tin tin = Tin::random_points(test::kUnitSquare, 2000, 7, [](Vec2) { return 0.1; });
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    ASSERT_TRUE(stamp(tin, tool, {{0.5, 0.5}, 0.0, 0.0}, context).applied);
    const OutsideChange change = outside_change(tin, tool, {{0.55, 0.5}, 0.0, 0.0}, context, 0.12);
    expect_unchanged_outside(change, tool);
}

// ---- 3. The rim follows the pre-stamp terrain ----------------------------------------------

/// Max |after - before| along O, and the deviation a straight rim through O's own vertices
/// would have had (so the test can tell whether subdividing was needed at all).
struct RimError {
    double max_error = 0.0;
    double chord_error = 0.0;
};

RimError rim_error(Tin& tin, const Tool& tool, const ToolPlacement& at, SculptContext& context) {
    // The contour the stamp uses: O subdivided at the tool's rim spacing, in the world.
    std::vector<Vec2> outer;
    for (Vec2 p : subdivide_contour(tool.shape().outer, tool.rim_spacing()))
        outer.push_back(tool.to_world(at, p));
    const std::vector<Vec2> samples = densify(outer, 97);
    const std::vector<double> before = surface_at(tin, samples);
    RimError e;
    // Chords between the contour's own vertices, on the pre-stamp heights.
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const std::size_t a = i - i % 97;
        const std::size_t b = (a + 97) % samples.size();
        const double t = static_cast<double>(i % 97) / 97.0;
        e.chord_error =
            std::max(e.chord_error, std::abs((1.0 - t) * before[a] + t * before[b] - before[i]));
    }
    const StampReport r = stamp(tin, tool, at, context);
    EXPECT_TRUE(r.applied);
    const std::vector<double> after = surface_at(tin, samples);
    for (std::size_t i = 0; i < samples.size(); ++i)
        e.max_error = std::max(e.max_error, std::abs(after[i] - before[i]));
    return e;
}

TEST(Stamp, RimFollowsCurvedTerrainWithinTolerance) {
    Tin tin = Tin::random_points(test::kUnitSquare, 20000, 31, test::wavy_sand);
    SculptContext context(tin.domain());
    ToolSpec spec;
    spec.radius = 0.1;
    spec.control_points = 12;
    spec.rim_tolerance = 1e-4;
    const Tool tool = Tool::build(spec);
    ASSERT_DOUBLE_EQ(tool.rim_tolerance(), 1e-4);
    const RimError e = rim_error(tin, tool, {{0.45, 0.55}, 0.25, 0.02}, context);
    EXPECT_GT(e.chord_error, 3.0 * tool.rim_tolerance())
        << "the terrain is not curved enough for this test to mean anything";
    EXPECT_LE(e.max_error, tool.rim_tolerance() * (1.0 + 1e-9) + 1e-12);
    EXPECT_TRUE(mesh_is_sound(tin));

    // The default tolerance (1 % of the radius) on the shipped circle.
    const Tool circle = Tool::build(load_tool_asset("circle"));
    const RimError e2 = rim_error(tin, circle, {{0.7, 0.25}, 1.0, 0.02}, context);
    EXPECT_LE(e2.max_error, circle.rim_tolerance() * (1.0 + 1e-9) + 1e-12);
}

TEST(Stamp, RimFollowsTerrainAcrossAnEarlierGroove) {
    Tin tin = Tin::random_points(test::kUnitSquare, 10000, 32, rolling_sand);
    SculptContext context(tin.domain());
    // A groove 7 cm deep along y = 0.5 (absolute floor at 0.02 m).
    const Tool groove_tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.spacing = 0.01;
    settings.depth_mode = DepthMode::Absolute;
    settings.depth = 0.02;
    const std::vector<Vec2> path = {{0.2, 0.5}, {0.8, 0.5}};
    apply_stroke(tin, groove_tool, path, settings, context);
    ASSERT_TRUE(mesh_is_sound(tin));
    ASSERT_NEAR(*tin.height_at({0.5, 0.5}), 0.02, 1e-12);

    // A wider stamp whose rim crosses both groove walls twice.
    ToolSpec spec;
    spec.radius = 0.08;
    spec.control_points = 16;
    spec.rim_tolerance = 5e-4;
    const Tool tool = Tool::build(spec);
    const RimError e = rim_error(tin, tool, {{0.5, 0.53}, 0.1, 0.0}, context);
    EXPECT_GT(e.chord_error, 10.0 * tool.rim_tolerance());
    EXPECT_LE(e.max_error, tool.rim_tolerance() * (1.0 + 1e-9) + 1e-12)
        << "the rim does not follow the pre-stamp terrain where it crosses the groove";
    EXPECT_TRUE(mesh_is_sound(tin));
}

// ---- 4. A non-convex λ ---------------------------------------------------------------------

TEST(Stamp, LambdaLeavesNothingAboveTheProfileAndSparesItsNotch) {
    const Tool tool = Tool::build(load_tool_asset("lambda"));
    // The notch between the legs, from the test's own copy of the asset geometry (centimetres,
    // scale 0.01): the legs end at (2.5, -5) and (-2.6, -5), the crotch is at (0, 0.2).
    const std::vector<Vec2> notch_local = {
        {2.5 * 0.01, -5.0 * 0.01}, {0.0, 0.2 * 0.01}, {-2.6 * 0.01, -5.0 * 0.01}};
    const Vec2 notch_centroid = (notch_local[0] + notch_local[1] + notch_local[2]) / 3.0;
    ASSERT_FALSE(inside_polygon(notch_centroid, tool.shape().inner));
    ASSERT_LT(test::signed_area_ld(tool.shape().inner), 0.9L * 0.01L * 0.01L * 9.1L * 10.0L)
        << "the λ should be clearly smaller than its bounding box";

    for (const bool simplify : {true, false}) {
        SCOPED_TRACE(simplify ? "with simplification" : "without simplification");
        const Rect domain = Rect::from_size(0.3, 0.3);
        Tin tin = Tin::random_points(domain, 8000, 41, rolling_sand);
        SculptContext context(tin.domain());
        context.settings.simplify_after_edit = simplify;
        const ToolPlacement at{{0.15, 0.14}, 0.35, 0.06};
        const std::vector<Vec2> inner = world(at, tool.shape().inner);
        const std::vector<Vec2> outer = world(at, tool.shape().outer);
        const std::vector<Vec2> notch = world(at, notch_local);

        struct Kept {
            VertexId id;
            Vec2 p;
            double h;
        };
        std::vector<Kept> in_notch;
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            // In the notch and outside the λ (clear of O as well: that band is the tool's).
            if (inside_polygon(p, notch) && outside_by(p, outer, 1e-9))
                in_notch.push_back({v, p, tin.height(v)});
        }
        ASSERT_GE(in_notch.size(), 10u) << "the terrain should have vertices in the notch";

        ASSERT_TRUE(stamp(tin, tool, at, context).applied);
        EXPECT_TRUE(mesh_is_sound(tin));

        // No vertex inside the λ or on its border lies above the flat profile.
        std::size_t checked = 0;
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            if (!inside_polygon(p, inner) && distance_to_border(p, inner) > 1e-12) continue;
            ++checked;
            EXPECT_LE(tin.height(v), at.bottom + 1e-12) << "vertex at " << p.x << ", " << p.y;
        }
        EXPECT_GE(checked, inner.size());
        // The surface, not only the vertices: sample the λ densely.
        LocateHint hint;
        std::size_t sampled = 0;
        for (Vec2 p : test::random_points_in(Rect{{0.07, 0.06}, {0.23, 0.22}}, 20000, 4)) {
            if (!inside_by(p, inner, 1e-9)) continue;
            ++sampled;
            EXPECT_LE(*tin.height_at(p, &hint), at.bottom + 1e-12) << "at " << p.x << ", " << p.y;
        }
        EXPECT_GT(sampled, 1000u);
        // The notch is not the tool's: its vertices stay where they were, at their heights.
        for (const Kept& k : in_notch) {
            ASSERT_TRUE(tin.is_alive(k.id)) << "a vertex in the notch was removed";
            EXPECT_EQ(tin.position(k.id), k.p);
            EXPECT_EQ(tin.height(k.id), k.h) << "a vertex in the notch moved";
        }
    }
}

// ---- Generations ---------------------------------------------------------------------------

TEST(Stamp, ReleasesOlderConstraintsUnderTheNewFootprint) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 51, rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    const StampReport first = stamp(tin, tool, {{0.5, 0.5}, 0.0, 0.05}, context);
    const StampReport second = stamp(tin, tool, {{0.53, 0.5}, 0.0, 0.04}, context);
    ASSERT_TRUE(first.applied && second.applied);
    EXPECT_LT(first.generation, second.generation);
    EXPECT_GT(second.constraints_released, 0u);
    const std::vector<Vec2> outer2 = world({{0.53, 0.5}, 0.0, 0.04}, tool.shape().outer);
    std::size_t gen1_left = 0;
    for (const ConstraintInfo& c : tin.constraints()) {
        ASSERT_TRUE(c.generation == first.generation || c.generation == second.generation);
        if (c.generation != first.generation) continue;
        // No piece of the first stamp that is still constrained lies inside the second O: the
        // new tool owns its footprint. Pieces crossing O's border were split there, so a
        // surviving piece may end on the border but its midpoint is outside.
        for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
            const Vec2 a = tin.position(c.vertices[k]);
            const Vec2 b = tin.position(c.vertices[k + 1]);
            const Vec2 mid = (a + b) * 0.5;
            const bool strictly_inside =
                inside_polygon(mid, outer2) && distance_to_border(mid, outer2) > 1e-9;
            EXPECT_FALSE(strictly_inside)
                << "segment " << a.x << "," << a.y << " - " << b.x << "," << b.y;
            gen1_left += strictly_inside ? 0 : 1;
        }
    }
    // The part of the first rim outside the second O is the first tool's edge: it must stay.
    EXPECT_GT(gen1_left, 0u) << "the far side of the first stamp stays constrained";
    EXPECT_TRUE(mesh_is_sound(tin));
}

TEST(Stamp, ExpiredConstraintsAreReleasedWhereTheSurfaceAllows) {
    Tin tin = Tin::random_points(test::kUnitSquare, 2000, 52, rolling_sand);
    SculptContext context(tin.domain());
    context.settings.keep_generations = 5;
    const Tool tool = circle_tool(0.03);
    Generation last = 0;
    std::map<Generation, std::size_t> made;  // constraints each stamp left right after it
    for (int i = 0; i < 16; ++i) {           // far-apart stamps: no footprint overlaps another
        const Vec2 c{0.12 + 0.25 * (i % 4), 0.12 + 0.25 * (i / 4)};
        last = stamp(tin, tool, {c, 0.0, 0.04}, context).generation;
        for (const ConstraintInfo& k : tin.constraints())
            made[last] += k.generation == last;
    }
    std::size_t expired_made = 0;
    for (const auto& [g, n] : made)
        expired_made += g + 5 < last ? n : 0;
    // An expired constraint is released unless releasing it would re-triangulate (some piece is
    // not Delaunay): the surface must not change just because time passed. So every survivor
    // older than the window has a piece that is not clearly Delaunay, by an independent
    // in-circle test.
    const auto not_delaunay = test::edges_not_clearly_delaunay(tin);
    std::size_t expired_survivors = 0;
    std::size_t young = 0;
    for (const ConstraintInfo& c : tin.constraints()) {
        if (c.generation + 5 >= last) {
            ++young;
            continue;
        }
        ++expired_survivors;
        bool has_non_delaunay_piece = false;
        for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
            std::uint32_t a = c.vertices[k].value, b = c.vertices[k + 1].value;
            if (a > b) std::swap(a, b);
            has_non_delaunay_piece = has_non_delaunay_piece || not_delaunay.count({a, b}) > 0;
        }
        EXPECT_TRUE(has_non_delaunay_piece)
            << "generation " << c.generation << " survived though all its pieces are Delaunay";
    }
    EXPECT_GT(young, 0u);
    // Expiry does release: fewer expired constraints survive than their stamps made.
    EXPECT_GT(expired_made, 0u);
    EXPECT_LT(expired_survivors, expired_made);
    EXPECT_TRUE(mesh_is_sound(tin));
}

}  // namespace
}  // namespace sandtin
