// Pouring and removing sand, and the artist brushes. Oracles: Tin::volume() and the brute-force
// per-triangle volume, the documented falloff formulas evaluated per vertex, the analytic
// integral of the falloff over the disc, bedrock read back per vertex, variance of a noisy patch,
// an analytic plane.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/brushes.hpp"
#include "tools/sand.hpp"

namespace sandtin {
namespace {

using test::live_ids;
using test::mesh_is_sound;

/// Heights of the live vertices by id.
std::unordered_map<std::uint32_t, double> heights(const Tin& tin) {
    std::unordered_map<std::uint32_t, double> h;
    for (VertexId v : live_ids(tin))
        h[v.value] = tin.height(v);
    return h;
}

VertexId nearest_vertex(const Tin& tin, Vec2 c) {
    VertexId best;
    double d = 1e300;
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), c) < d) {
            d = distance(tin.position(v), c);
            best = v;
        }
    }
    return best;
}

// ---- 10. Pour and remove ---------------------------------------------------------------------

TEST(Sand, PourAddsExactlyTheVolume) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 401, test::rolling_sand);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    const auto h0 = heights(tin);
    const double v0 = tin.volume();
    PourSettings s;
    s.radius = 0.03;
    const double volume = 1e-4;
    const Vec2 c{0.4, 0.6};
    const PourReport r = pour_sand(tin, c, volume, s, context);
    EXPECT_NEAR(tin.volume() - v0, volume, 1e-12 * volume);
    EXPECT_NEAR(test::brute_force_volume(tin) - v0, volume, 1e-12 * volume);
    EXPECT_NEAR(r.volume, volume, 1e-12 * volume);
    EXPECT_GT(r.vertices_changed, 10u);
    EXPECT_TRUE(mesh_is_sound(tin));
    // Vertices beyond the radius keep their heights; the pile peaks at the centre.
    for (const auto& [id, h] : h0) {
        const VertexId v{id};
        ASSERT_TRUE(tin.is_alive(v));
        if (distance(tin.position(v), c) > s.radius) {
            EXPECT_EQ(tin.height(v), h);
        } else if (distance(tin.position(v), c) < s.radius) {
            EXPECT_GT(tin.height(v), h);
        }
    }
    EXPECT_GT(*tin.height_at(c), test::rolling_sand(c) + 0.5 * volume / (std::numbers::pi * 9e-4));
}

TEST(Sand, PourOnTwoTrianglesRefinesAndAddsExactlyTheVolume) {
    Tin tin = Tin::flat_rectangle(test::kUnitSquare, 0.1);
    ASSERT_EQ(tin.vertex_count(), 4u);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    const double v0 = tin.volume();
    PourSettings s;
    s.radius = 0.05;
    const double volume = 1e-4;
    const Vec2 c{0.5, 0.5};
    const PourReport r = pour_sand(tin, c, volume, s, context);
    EXPECT_GT(r.vertices_inserted, 20u) << "a pour on two triangles needs points to have a shape";
    EXPECT_EQ(tin.vertex_count(), 4u + r.vertices_inserted);
    EXPECT_NEAR(tin.volume() - v0, volume, 1e-12 * volume);
    EXPECT_NEAR(test::brute_force_volume(tin) - v0, volume, 1e-12 * volume);
    EXPECT_TRUE(mesh_is_sound(tin));
    // A round pile: the top at the centre, sand raised half-way out in every direction, and
    // flat sand beyond the radius plus one refined edge (r / 4): no triangle reaching there
    // has a corner inside the disc.
    const double top = *tin.height_at(c);
    LocateHint hint;
    for (int k = 0; k < 16; ++k) {
        const Vec2 dir{std::cos(k * std::numbers::pi / 8), std::sin(k * std::numbers::pi / 8)};
        EXPECT_LT(*tin.height_at(c + dir * (0.5 * s.radius), &hint), top);
        EXPECT_GT(*tin.height_at(c + dir * (0.5 * s.radius), &hint), 0.1);
        EXPECT_NEAR(*tin.height_at(c + dir * (1.25 * s.radius + 1e-3), &hint), 0.1, 1e-15);
    }
    // Pouring nothing changes nothing; a bad volume throws.
    const test::TinState before = test::capture(tin);
    pour_sand(tin, c, 0.0, s, context);
    test::expect_snapshots_equal(before.snapshot, tin.snapshot());
    EXPECT_THROW(pour_sand(tin, c, -1.0, s, context), std::invalid_argument);
    EXPECT_THROW(pour_sand(tin, c, std::nan(""), s, context), std::invalid_argument);
}

TEST(Sand, RemoveNeverGoesBelowBedrockAndReportsWhatItTook) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 402, test::rolling_sand);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    // Two millimetres of sand over the bedrock everywhere.
    for (VertexId v : live_ids(tin))
        tin.set_bedrock(v, tin.height(v) - 0.002);
    PourSettings s;
    s.radius = 0.03;
    const Vec2 c{0.55, 0.45};

    // A little: all of it comes out.
    double v0 = tin.volume();
    PourReport r = remove_sand(tin, c, 1e-7, s, context);
    EXPECT_NEAR(r.volume, -1e-7, 1e-12 * 1e-7 + 1e-16);
    EXPECT_NEAR(tin.volume() - v0, -1e-7, 1e-12 * 1e-7 + 1e-16);

    // Far more than the disc holds: it stops at the bedrock and says how much it took.
    v0 = tin.volume();
    const auto h0 = heights(tin);
    r = remove_sand(tin, c, 1e-3, s, context);
    const double taken = v0 - tin.volume();
    // (Tin::volume() sums ~0.1 m^3, so its rounding is ~1e-17 m^3.)
    EXPECT_NEAR(r.volume, -taken, 1e-12 * taken + 1e-16);
    EXPECT_NEAR(test::brute_force_volume(tin), tin.volume(), 1e-12);
    EXPECT_GT(taken, 0.0);
    EXPECT_LT(taken, 1e-3);
    // At most the sand of the vertices in the disc: 2 mm over their lumped areas, which lie
    // within one refined edge (r / 4) of the disc.
    EXPECT_LT(taken, 0.002 * std::numbers::pi * std::pow(1.25 * s.radius, 2));
    const VertexArrays& va = tin.vertices();
    std::size_t bare = 0;
    for (VertexId v : live_ids(tin)) {
        EXPECT_GE(va.height[v.index()], va.bedrock[v.index()]) << "below bedrock";
        const double d = distance(tin.position(v), c);
        if (d < 0.9 * s.radius) {
            EXPECT_EQ(va.height[v.index()], va.bedrock[v.index()]) << "sand left at d = " << d;
            ++bare;
        }
        const auto old = h0.find(v.value);
        if (d > s.radius && old != h0.end()) {  // untouched
            EXPECT_EQ(va.height[v.index()], old->second);
        }
    }
    EXPECT_GT(bare, 10u);
    EXPECT_TRUE(mesh_is_sound(tin));
    // Nothing left to take: a further removal takes nothing.
    v0 = tin.volume();
    r = remove_sand(tin, c + Vec2{0.002, 0.0}, 1e-4, s, context);
    EXPECT_NEAR(r.volume, tin.volume() - v0, 1e-15);
}

// The bedrock is not erodible: a removal along a path, whose dabs refine and simplify sand the
// earlier dabs dug down to it, must leave every vertex on or above it, and the bedrock where it
// was. The volume compensation of those refinements lowered vertices (and the bedrock with
// them) 4.4 mm below a flat bedrock. Oracle: the flat bedrock plane, 2 cm up.
TEST(Sand, RemoveAlongAPathNeverDigsBelowAFlatBedrock) {
    for (const bool simplify : {true, false}) {
        SCOPED_TRACE(simplify ? "with simplification" : "without simplification");
        Tin tin = Tin::random_points(test::kUnitSquare, 20000, 403, [](Vec2 p) {
            return 0.03 + 0.008 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y);
        });
        for (VertexId v : live_ids(tin))
            tin.set_bedrock(v, 0.02);
        SculptContext context(tin.domain());
        context.settings.simplify_after_edit = simplify;
        PourSettings s;
        s.radius = 0.03;
        const double v0 = tin.volume();
        double reported = 0.0;
        for (int k = 0; k <= 20; ++k) {  // the script's path 0.5 -> 0.6 at radius / 2 spacing
            const Vec2 at{0.5 + 0.005 * k, 0.6};
            reported += remove_sand(tin, at, 0.01 / 21.0, s, context).volume;
            if (simplify) context.simplifier.run(tin, context.settings.simplify);
        }
        const VertexArrays& va = tin.vertices();
        double lowest = 1.0, lowest_bedrock = 1.0;
        for (VertexId v : live_ids(tin)) {
            lowest = std::min(lowest, va.height[v.index()]);
            lowest_bedrock = std::min(lowest_bedrock, va.bedrock[v.index()]);
        }
        EXPECT_GE(lowest, 0.02 - 1e-15);
        EXPECT_GE(lowest_bedrock, 0.02 - 1e-15);
        EXPECT_LT(lowest, 0.02 + 1e-12) << "the premise: the path digs down to the bedrock";
        EXPECT_NEAR(tin.volume() - v0, reported, 1e-12);
        EXPECT_TRUE(mesh_is_sound(tin));
    }
}

// ---- 11. Brushes -----------------------------------------------------------------------------

double smooth_falloff(double t) {
    return t < 1.0 ? 1.0 - t * t * (3.0 - 2.0 * t) : 0.0;
}

TEST(Brush, RaiseAndLowerFollowTheFalloffAndPeakAtTheCentre) {
    for (const BrushKind kind : {BrushKind::Raise, BrushKind::Lower}) {
        const double sign = kind == BrushKind::Raise ? 1.0 : -1.0;
        SCOPED_TRACE(sign > 0 ? "raise" : "lower");
        Tin tin = Tin::random_points(test::kUnitSquare, 5000, 411, test::rolling_sand);
        SculptContext context(tin.domain());
        context.settings.simplify_after_edit = false;
        BrushSettings b;
        b.kind = kind;
        b.radius = 0.05;
        b.strength = 0.004;
        b.falloff = Falloff::Smooth;
        const Vec2 c{0.52, 0.47};
        const auto h0 = heights(tin);
        const Tin before = Tin::from_snapshot(tin.snapshot());
        const double v0 = tin.volume();
        const BrushReport r = apply_brush(tin, c, b, context);
        EXPECT_TRUE(mesh_is_sound(tin));
        // Every vertex that existed moved by strength * falloff(d / r), exactly.
        for (const auto& [id, h] : h0) {
            const VertexId v{id};
            const double t = distance(tin.position(v), c) / b.radius;
            EXPECT_NEAR(tin.height(v) - h, sign * b.strength * smooth_falloff(t), 1e-15);
        }
        // The extreme change, over all vertices (new ones measured against the sand before),
        // is at the vertex nearest the centre.
        const VertexId centre_vertex = nearest_vertex(tin, c);
        double best = -1e300;
        VertexId best_v;
        LocateHint hint;
        for (VertexId v : live_ids(tin)) {
            const double change =
                sign * (tin.height(v) - *before.height_at(tin.position(v), &hint));
            if (change > best) {
                best = change;
                best_v = v;
            }
        }
        EXPECT_EQ(best_v, centre_vertex);
        // The volume: strength times the integral of the falloff over the disc,
        // 2 pi r^2 * int_0^1 (1 - 3t^2 + 2t^3) t dt = 0.3 pi r^2.
        const double expected = sign * b.strength * 0.3 * std::numbers::pi * b.radius * b.radius;
        EXPECT_NEAR(tin.volume() - v0, expected, 0.1 * std::abs(expected));
        EXPECT_NEAR(r.volume_change, tin.volume() - v0, 1e-12);
        EXPECT_GT(r.vertices_changed, 20u);
    }
}

/// A reproducible noise in [-1, 1] from a position.
double noise(Vec2 p) {
    const double s = std::sin(p.x * 12345.678 + p.y * 91011.1213) * 43758.5453;
    return 2.0 * (s - std::floor(s)) - 1.0;
}

double variance_in_disc(const Tin& tin, Vec2 c, double r) {
    double sum = 0.0, sum2 = 0.0;
    std::size_t n = 0;
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), c) >= r) continue;
        sum += tin.height(v);
        sum2 += tin.height(v) * tin.height(v);
        ++n;
    }
    const double mean = sum / static_cast<double>(n);
    return sum2 / static_cast<double>(n) - mean * mean;
}

TEST(Brush, SmoothCalmsNoise) {
    Tin tin = Tin::random_points(test::kUnitSquare, 20000, 421,
                                 [](Vec2 p) { return 0.1 + 0.002 * noise(p); });
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    BrushSettings b;
    b.kind = BrushKind::Smooth;
    b.radius = 0.1;
    b.strength = 1.0;
    b.falloff = Falloff::Constant;
    const Vec2 c{0.5, 0.5};
    const double before = variance_in_disc(tin, c, 0.05);
    ASSERT_GT(before, 1e-7);
    apply_brush(tin, c, b, context);
    const double after = variance_in_disc(tin, c, 0.05);
    EXPECT_LT(after, 0.5 * before) << before << " -> " << after;
    EXPECT_TRUE(mesh_is_sound(tin));
}

TEST(Brush, SmoothLeavesAPlaneUnchanged) {
    // A sloped plane is as smooth as sand gets: smoothing it must not move it.
    const test::Plane plane{0.05, -0.03, 0.1};
    Tin tin = Tin::random_points(test::kUnitSquare, 5000, 422, plane);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    BrushSettings b;
    b.kind = BrushKind::Smooth;
    b.radius = 0.1;
    b.strength = 1.0;
    b.falloff = Falloff::Constant;
    apply_brush(tin, {0.5, 0.5}, b, context);
    double worst = 0.0;
    for (VertexId v : live_ids(tin))
        worst = std::max(worst, std::abs(tin.height(v) - plane(tin.position(v))));
    EXPECT_LE(worst, 1e-12) << "smoothing moved a plane by up to " << worst << " m";
}

TEST(Brush, FlattenMovesHeightsTowardTheTarget) {
    Tin tin = Tin::random_points(test::kUnitSquare, 5000, 431, test::rolling_sand);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    BrushSettings b;
    b.kind = BrushKind::Flatten;
    b.radius = 0.08;
    b.strength = 0.5;
    b.falloff = Falloff::Smooth;
    b.flatten_to = 0.1;
    const Vec2 c{0.3, 0.7};
    const auto h0 = heights(tin);
    apply_brush(tin, c, b, context);
    std::size_t moved = 0;
    for (const auto& [id, h] : h0) {
        const VertexId v{id};
        const double w = smooth_falloff(distance(tin.position(v), c) / b.radius);
        const double expected = h + b.strength * w * (0.1 - h);
        EXPECT_NEAR(tin.height(v), expected, 1e-15);
        EXPECT_LE(std::abs(tin.height(v) - 0.1), std::abs(h - 0.1) + 1e-15);
        moved += w > 0.0 ? 1 : 0;
    }
    EXPECT_GT(moved, 20u);
    EXPECT_TRUE(mesh_is_sound(tin));
    // Strength 1 with a constant falloff: exactly level inside the radius.
    b.strength = 1.0;
    b.falloff = Falloff::Constant;
    apply_brush(tin, {0.6, 0.3}, b, context);
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), {0.6, 0.3}) < b.radius * (1.0 - 1e-12)) {
            EXPECT_NEAR(tin.height(v), 0.1, 1e-15);
        }
    }
}

TEST(Brush, PaintSetsMaterialWithinTheRadiusOnly) {
    Tin tin = Tin::random_points(test::kUnitSquare, 5000, 441, test::rolling_sand);
    SculptContext context(tin.domain());
    BrushSettings b;
    b.kind = BrushKind::PaintMaterial;
    b.radius = 0.06;
    b.material = 7;
    b.moisture = 0.25f;
    const Vec2 c{0.5, 0.5};
    const std::size_t n = tin.vertex_count();
    const double v0 = tin.volume();
    const BrushReport r = apply_brush(tin, c, b, context);
    EXPECT_EQ(tin.vertex_count(), n) << "painting needs no new points";
    EXPECT_EQ(tin.volume(), v0);
    std::size_t painted = 0;
    const VertexArrays& va = tin.vertices();
    for (VertexId v : live_ids(tin)) {
        const double d = distance(tin.position(v), c);
        if (d < b.radius * (1.0 - 1e-12)) {
            EXPECT_EQ(va.material[v.index()], 7) << "d = " << d;
            EXPECT_EQ(va.moisture[v.index()], 0.25f) << "d = " << d;
            ++painted;
        } else if (d > b.radius * (1.0 + 1e-12)) {
            EXPECT_EQ(va.material[v.index()], 0) << "d = " << d;
            EXPECT_EQ(va.moisture[v.index()], 0.0f) << "d = " << d;
        }
    }
    EXPECT_EQ(r.vertices_changed, painted);
    EXPECT_GT(painted, 30u);
    // The same material at another moisture is a change too (the editor's Paint moisture).
    b.moisture = 0.5f;
    EXPECT_EQ(apply_brush(tin, c, b, context).vertices_changed, painted);
    EXPECT_EQ(apply_brush(tin, c, b, context).vertices_changed, 0u);
    b.moisture = 1.5f;
    EXPECT_THROW(apply_brush(tin, c, b, context), std::invalid_argument);
}

// How far the surface moved outside the disc (centre, reach), sampled on a grid around it.
double worst_change_outside(const Tin& before, const Tin& after, Vec2 centre, double reach) {
    double worst = 0.0;
    LocateHint before_hint, after_hint;
    const Vec2 half{3.0 * reach, 3.0 * reach};
    for (Vec2 p : test::grid_points(Rect{centre - half, centre + half}, 181, 181)) {
        if (!before.domain().contains(p) || distance(p, centre) <= reach) continue;
        worst = std::max(
            worst, std::abs(*after.height_at(p, &after_hint) - *before.height_at(p, &before_hint)));
    }
    return worst;
}

// On an imported elevation model (triangles tens of metres wide, far from flat), the points a
// dab or a pour refines with used to re-triangulate faces well outside it by Delaunay's rule:
// on a 2 m grid a 2 m raise dab moved the surface 0.28 m up to 5.5 m away. Now the bent edges
// they would remove are fenced first. Oracle: the surface before the edit. Beyond the disc and
// two refinement spacings it may move by no more than the fence's tolerance: the triangles of
// the vertices the dab moves reach one spacing out, and the simplifier, removing a vertex one
// spacing inside the disc, levels its volume change over its ring, whose triangles reach one
// more.
// The same edits without the fence show the premise.
TEST(Brush, OnACoarseElevationModelDabsAndPoursChangeNothingBeyondTheirDisc) {
    const Tin model = test::coarse_hills_model();
    for (const double radius : {2.0, 20.0}) {
        for (const Vec2 at : test::coarse_model_placements(model, true)) {
            SCOPED_TRACE(std::to_string(radius) + " m at " + std::to_string(at.x) + ", " +
                         std::to_string(at.y));
            BrushSettings raise;
            raise.kind = BrushKind::Raise;
            raise.radius = radius;
            raise.strength = 0.1 * radius;
            PourSettings pour;
            pour.radius = radius;
            for (const bool fenced : {true, false}) {
                Tin dabbed = Tin::from_snapshot(model.snapshot());
                SculptContext dab_context(dabbed.domain());
                dab_context.settings.fence_coarse_edges = fenced;
                const BrushReport b = apply_brush(dabbed, at, raise, dab_context);
                ASSERT_TRUE(mesh_is_sound(dabbed));
                Tin poured = Tin::from_snapshot(model.snapshot());
                SculptContext pour_context(poured.domain());
                pour_context.settings.fence_coarse_edges = fenced;
                const PourReport p = pour_sand(poured, at, radius * radius, pour, pour_context);
                ASSERT_TRUE(mesh_is_sound(poured));
                const double tolerance =
                    std::min(0.01 * radius, dab_context.settings.simplify.tolerance);
                const double dab_moved =
                    worst_change_outside(model, dabbed, at, radius + 2.0 * radius / 6.0);
                const double pour_moved =
                    worst_change_outside(model, poured, at, radius + 2.0 * radius / 4.0);
                if (fenced) {
                    EXPECT_GT(b.edges_fenced, 0u) << "the premise: bent edges to fence";
                    EXPECT_LE(dab_moved, tolerance) << "the dab re-shaped the surface outside it";
                    EXPECT_LE(pour_moved, tolerance) << "the pour re-shaped the surface outside it";
                } else {
                    EXPECT_EQ(b.edges_fenced + p.edges_fenced, 0u);
                    EXPECT_GT(std::max(dab_moved, pour_moved), 10.0 * tolerance)
                        << "the premise: unfenced, the refinement re-shapes the surface";
                }
            }
        }
    }
}

TEST(Brush, BadSettingsThrow) {
    Tin tin = Tin::random_points(test::kUnitSquare, 100, 451);
    SculptContext context(tin.domain());
    BrushSettings b;
    b.radius = 0.0;
    EXPECT_THROW(apply_brush(tin, {0.5, 0.5}, b, context), std::invalid_argument);
    b = BrushSettings{};
    b.strength = -1.0;
    EXPECT_THROW(apply_brush(tin, {0.5, 0.5}, b, context), std::invalid_argument);
    b = BrushSettings{};
    b.kind = BrushKind::Smooth;
    b.strength = 1.5;
    EXPECT_THROW(apply_brush(tin, {0.5, 0.5}, b, context), std::invalid_argument);
    b = BrushSettings{};
    EXPECT_THROW(apply_brush(tin, {std::nan(""), 0.5}, b, context), std::invalid_argument);
    // Far outside the domain: nothing happens.
    const test::TinState before = test::capture(tin);
    apply_brush(tin, {5.0, 5.0}, BrushSettings{}, context);
    test::expect_snapshots_equal(before.snapshot, tin.snapshot());
}

}  // namespace
}  // namespace sandtin
