// Automatic simplification: planarity residuals, the simplifier queue, planar patch removal,
// and the acceptance criterion that a flattened region loses at least 90 % of its interior
// vertices. Oracles: analytic planes, vertex counts by brute force over positions, snapshots
// compared field by field when an edit must change nothing, volumes and surfaces sampled on
// the plane.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/plane_oracle.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/brushes.hpp"
#include "tools/simplifier.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin {
namespace {

using test::inside_by;
using test::live_ids;
using test::mesh_is_sound;
using test::on_domain_border;

const test::Plane kSlope{0.05, -0.03, 0.1};

std::size_t count_inside(const Tin& tin, std::span<const Vec2> poly, double margin) {
    std::size_t n = 0;
    for (VertexId v : live_ids(tin))
        n += inside_by(tin.position(v), poly, margin) ? 1 : 0;
    return n;
}

std::size_t count_in_disc(const Tin& tin, Vec2 c, double r) {
    std::size_t n = 0;
    for (VertexId v : live_ids(tin))
        n += distance(tin.position(v), c) < r ? 1 : 0;
    return n;
}

std::vector<VertexId> interior_in_disc(const Tin& tin, Vec2 c, double r) {
    std::vector<VertexId> out;
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), c) < r && !on_domain_border(tin.domain(), tin.position(v)))
            out.push_back(v);
    }
    return out;
}

/// Grows a set of interior vertices until the triangles around it form a disc: no vertex
/// enclosed without being in the set, no pinch (a vertex where the boundary passes twice), a
/// single boundary loop. Computed from triangles() only.
std::vector<VertexId> close_to_disc(const Tin& tin, std::vector<VertexId> set) {
    for (int round = 0; round < 100; ++round) {
        std::set<VertexId> in(set.begin(), set.end());
        std::map<std::pair<VertexId, VertexId>, bool> directed;  // edge -> in a region face
        std::vector<test::Tri> region;
        for (const test::Tri& t : tin.triangles()) {
            const bool r = in.count(t[0]) || in.count(t[1]) || in.count(t[2]);
            for (int i = 0; i < 3; ++i)
                directed[{t[static_cast<std::size_t>(i)],
                          t[static_cast<std::size_t>((i + 1) % 3)]}] = r;
            if (r) region.push_back(t);
        }
        std::map<VertexId, std::vector<VertexId>> next;  // boundary: region on the left
        std::set<VertexId> corners;
        for (const test::Tri& t : region) {
            for (int i = 0; i < 3; ++i) {
                const VertexId a = t[static_cast<std::size_t>(i)];
                const VertexId b = t[static_cast<std::size_t>((i + 1) % 3)];
                corners.insert(a);
                const auto twin = directed.find({b, a});
                if (twin == directed.end() || !twin->second) next[a].push_back(b);
            }
        }
        std::vector<VertexId> add;
        for (VertexId v : corners) {
            if (!in.count(v) && !next.count(v)) add.push_back(v);  // enclosed
        }
        for (const auto& [v, to] : next) {
            if (to.size() > 1) add.push_back(v);  // pinch
        }
        if (add.empty()) {
            // Loops: keep the longest as the outer boundary, fill the others.
            std::set<VertexId> seen;
            std::vector<std::vector<VertexId>> loops;
            for (const auto& [v, to] : next) {
                if (seen.count(v)) continue;
                std::vector<VertexId> loop;
                for (VertexId w = v; !seen.count(w); w = next.at(w).front()) {
                    seen.insert(w);
                    loop.push_back(w);
                }
                loops.push_back(loop);
            }
            if (loops.size() <= 1) return set;
            std::sort(loops.begin(), loops.end(),
                      [](const auto& a, const auto& b) { return a.size() > b.size(); });
            for (std::size_t k = 1; k < loops.size(); ++k)
                add.insert(add.end(), loops[k].begin(), loops[k].end());
        }
        set.insert(set.end(), add.begin(), add.end());
    }
    ADD_FAILURE() << "could not close the set to a disc";
    return set;
}

// ---- 7. A flattened region loses >= 90 % of its interior vertices ---------------------------

TEST(Simplifier, FlatStampRemovesAtLeast90PercentOfInteriorVertices) {
    ToolSpec spec;
    spec.radius = 0.1;
    spec.control_points = 24;
    const Tool tool = Tool::build(spec);
    const ToolPlacement at{{0.5, 0.5}, 0.0, 0.05};
    const std::vector<Vec2> inner = test::rotate_all(tool.shape().inner, at.centre, at.angle);
    for (const bool simplify : {false, true}) {
        Tin tin = Tin::random_points(test::kUnitSquare, 20000, 301, test::rolling_sand);
        SculptContext context(tin.domain());
        context.settings.simplify_after_edit = simplify;
        const std::size_t before = count_inside(tin, inner, 1e-9);
        ASSERT_GT(before, 400u);
        ASSERT_TRUE(stamp(tin, tool, at, context).applied);
        EXPECT_TRUE(mesh_is_sound(tin));
        const std::size_t after = count_inside(tin, inner, 1e-9);
        if (simplify) {
            EXPECT_LE(after, before / 10) << before << " -> " << after;
        } else {
            // Without simplification the floor keeps them: the removal above is the
            // simplifier's doing, not the stamp's.
            EXPECT_GE(after, before);
        }
    }
}

TEST(Simplifier, FlattenBrushThenSimplifyRemovesAtLeast90PercentOfInteriorVertices) {
    Tin tin = Tin::random_points(test::kUnitSquare, 20000, 302, test::rolling_sand);
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    BrushSettings b;
    b.kind = BrushKind::Flatten;
    b.radius = 0.1;
    b.strength = 1.0;
    b.falloff = Falloff::Constant;
    b.flatten_to = 0.08;
    const Vec2 c{0.45, 0.55};
    apply_brush(tin, c, b, context);
    // The interior of the flattened disc: well inside, where every neighbour was flattened.
    const double r = 0.8 * b.radius;
    for (VertexId v : live_ids(tin)) {
        if (distance(tin.position(v), c) < b.radius * (1.0 - 1e-12)) {
            EXPECT_NEAR(tin.height(v), 0.08, 1e-15);
        }
    }
    const std::size_t before = count_in_disc(tin, c, r);
    ASSERT_GT(before, 300u);
    for (VertexId v : live_ids(tin))
        context.simplifier.enqueue(v);
    const SimplifyReport rep = context.simplifier.run(tin, context.settings.simplify);
    EXPECT_TRUE(mesh_is_sound(tin));
    const std::size_t after = count_in_disc(tin, c, r);
    EXPECT_LE(after, before / 10) << before << " -> " << after;
    EXPECT_GE(rep.removed, before - after);
    // The flat disc is still flat.
    LocateHint hint;
    for (Vec2 p : test::random_points_in(Rect{{0.37, 0.47}, {0.53, 0.63}}, 2000, 3)) {
        if (distance(p, c) < r) {
            EXPECT_NEAR(*tin.height_at(p, &hint), 0.08, 1e-12);
        }
    }
}

// ---- 14. The simplifier and planar patches --------------------------------------------------

TEST(Simplifier, PlanarityResidualIsZeroOnAPlaneAndPositiveOnABump) {
    Tin tin = Tin::random_points(test::kUnitSquare, 2000, 311, kSlope);
    std::size_t interior = 0;
    for (VertexId v : live_ids(tin)) {
        if (tin.is_boundary(v)) {
            EXPECT_EQ(planarity_residual(tin, v), std::numeric_limits<double>::infinity());
            continue;
        }
        ++interior;
        EXPECT_LE(planarity_residual(tin, v), 1e-12);
    }
    EXPECT_GT(interior, 1900u);
    // Raise one vertex by delta: the least-squares plane through it and its ring misses it by
    // delta (1 - leverage), at least delta / 3 for a vertex surrounded by its neighbours, and
    // no point by more than delta.
    const double delta = 0.003;
    std::size_t bumped = 0;
    for (VertexId v : live_ids(tin)) {
        if (tin.is_boundary(v) || v.index() % 97 != 0) continue;
        const double h = tin.height(v);
        tin.set_height(v, h + delta);
        const double r = planarity_residual(tin, v);
        EXPECT_GE(r, delta / 3.0);
        EXPECT_LE(r, delta * (1.0 + 1e-9));
        tin.set_height(v, h);
        EXPECT_LE(planarity_residual(tin, v), 1e-12);
        ++bumped;
    }
    EXPECT_GT(bumped, 10u);
    // A vertex on a constraint is never a candidate.
    const std::vector<VertexId> ids =
        tin.insert_points(std::vector<Vec2>{{0.3, 0.3}, {0.6, 0.4}},
                          std::vector<double>{kSlope({0.3, 0.3}), kSlope({0.6, 0.4})});
    tin.insert_constraint(ids[0], ids[1], 1);
    EXPECT_EQ(planarity_residual(tin, ids[0]), std::numeric_limits<double>::infinity());
}

/// Max vertical distance of v and its ring from their least-squares plane, by the independent
/// SVD fit.
double residual_by_svd(const Tin& tin, VertexId v) {
    std::vector<VertexId> ring;
    tin.neighbours(v, ring);
    std::vector<Vec2> xy = {tin.position(v)};
    std::vector<double> z = {tin.height(v)};
    for (VertexId w : ring) {
        xy.push_back(tin.position(w));
        z.push_back(tin.height(w));
    }
    return test::plane_residual_by_svd(xy, z);
}

TEST(Simplifier, PlanarityResidualMatchesAnIndependentFitOnCurvedSand) {
    const auto dune = [](Vec2 p) { return 0.02 * std::sin(9.0 * p.x) * std::cos(7.0 * p.y); };
    // Ordinary stars, which the normal equations fit, and stars squeezed 10^7 times flatter
    // than they are long (a grid of 0.1 x 10^-8 cells), whose pivot ratio sends them to QR.
    const Tin random = Tin::random_points(test::kUnitSquare, 3000, 41, dune);
    const Tin squeezed = Tin::regular_grid(Rect::from_size(1.0, 1e-7), 10, 10, [](Vec2 p) {
        return 0.02 * std::sin(9.0 * p.x) + 1e12 * p.y * p.y;
    });
    for (const Tin* tin : {&random, &squeezed}) {
        std::size_t compared = 0;
        for (VertexId v : live_ids(*tin)) {
            if (tin->is_boundary(v)) continue;
            const double expected = residual_by_svd(*tin, v);
            EXPECT_NEAR(planarity_residual(*tin, v), expected, 1e-9 * expected + 1e-15)
                << "vertex " << v.index();
            ++compared;
        }
        EXPECT_GT(compared, 60u);
    }
}

TEST(Simplifier, NeverRemovesBorderOrConstrainedVertices) {
    // Flat sand with points along the border and a constrained polyline through it: every
    // other vertex is redundant.
    Tin tin = test::smooth_terrain(
        test::kUnitSquare, 3000, 321, [](Vec2) { return 0.1; }, 0.05);
    const std::vector<Vec2> line = {{0.2, 0.2}, {0.4, 0.35}, {0.5, 0.3}, {0.7, 0.6}, {0.6, 0.8}};
    const std::vector<VertexId> ids =
        tin.insert_points(line, std::vector<double>(line.size(), 0.1));
    tin.insert_constraint(ids, /*closed=*/false, 1);
    std::vector<VertexId> border;
    for (VertexId v : live_ids(tin)) {
        if (on_domain_border(tin.domain(), tin.position(v))) border.push_back(v);
    }
    ASSERT_GT(border.size(), 4u);
    Simplifier s;
    for (VertexId v : live_ids(tin))
        s.enqueue(v);
    EXPECT_EQ(s.queued(), tin.vertex_count());
    SimplifySettings settings;
    settings.tolerance = 1e-3;
    const double v0 = tin.volume();
    const SimplifyReport r = s.run(tin, settings);
    EXPECT_EQ(s.queued(), 0u);
    EXPECT_TRUE(mesh_is_sound(tin));
    for (VertexId v : border)
        EXPECT_TRUE(tin.is_alive(v)) << "border vertex removed";
    for (VertexId v : ids)
        EXPECT_TRUE(tin.is_alive(v)) << "constraint vertex removed";
    // Everything else went (it was all flat).
    for (VertexId v : live_ids(tin)) {
        EXPECT_TRUE(on_domain_border(tin.domain(), tin.position(v)) || tin.is_on_constraint(v))
            << tin.position(v).x << ", " << tin.position(v).y;
    }
    EXPECT_EQ(r.removed, 3000u);
    EXPECT_NEAR(tin.volume(), v0, 1e-12);
    EXPECT_NEAR(r.volume_change, 0.0, 1e-12);
}

TEST(Simplifier, KeepsTheVerticesUnderAndBesideWaterAndTheWatersVolume) {
    // Flat sand, a puddle on its west half: the dry east half is simplified as before; no
    // vertex under the water or beside it goes, so the water's volume (sum of lumped area x
    // depth) is what it was, to the last bit of the vertices it stands on.
    Tin tin = test::smooth_terrain(
        test::kUnitSquare, 3000, 321, [](Vec2) { return 0.1; }, 0.05);
    std::vector<VertexId> wet;
    for (VertexId v : live_ids(tin)) {
        if (tin.position(v).x < 0.45 && !on_domain_border(tin.domain(), tin.position(v))) {
            tin.set_water_depth(v, 0.01);
            wet.push_back(v);
        }
    }
    ASSERT_GT(wet.size(), 500u);
    const double water = test::water_volume(tin);
    Simplifier s;
    for (VertexId v : live_ids(tin))
        s.enqueue(v);
    SimplifySettings settings;
    settings.tolerance = 1e-3;
    const SimplifyReport r = s.run(tin, settings);
    EXPECT_TRUE(mesh_is_sound(tin));
    for (VertexId v : wet)
        EXPECT_TRUE(tin.is_alive(v)) << "a vertex under the water was removed";
    EXPECT_EQ(test::water_volume(tin), water);
    // The dry half went (it was all flat), but for the ring beside the water and the border.
    EXPECT_GT(r.removed, 1000u);
    for (VertexId v : live_ids(tin)) {
        if (tin.position(v).x > 0.6) {
            EXPECT_TRUE(on_domain_border(tin.domain(), tin.position(v)))
                << tin.position(v).x << ", " << tin.position(v).y;
        }
    }
}

TEST(Simplifier, RemovalsStayWithinToleranceOnCurvedSand) {
    // On curved sand only vertices within d_m of their ring's plane go, so the surface moves
    // by little: check it on a grid against the analytic sand.
    Tin tin = Tin::random_points(test::kUnitSquare, 4000, 331, test::rolling_sand);
    const Tin before = Tin::from_snapshot(tin.snapshot());
    Simplifier s;
    for (VertexId v : live_ids(tin))
        s.enqueue(v);
    SimplifySettings settings;
    settings.tolerance = 2e-4;
    settings.volume_policy = VolumePolicy::Report;
    const double v0 = tin.volume();
    const SimplifyReport r = s.run(tin, settings);
    EXPECT_GT(r.removed, 0u);
    EXPECT_LT(r.removed, 4000u);
    EXPECT_TRUE(mesh_is_sound(tin));
    // With VolumePolicy::Report the reported change is the measured one.
    EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-12);
    // Every removed vertex's height is still represented within a few tolerances (each
    // removal moves the surface by at most d_m at the vertex; neighbouring removals add up).
    for (VertexId v : live_ids(before)) {
        if (tin.is_alive(v)) continue;
        EXPECT_NEAR(*tin.height_at(before.position(v)), before.height(v), 4.0 * settings.tolerance);
    }
}

TEST(Simplifier, PlanarPatchOfADiscIsRemovedInOneStep) {
    Tin tin = Tin::random_points(test::kUnitSquare, 5000, 341, kSlope);
    const Vec2 c{0.5, 0.5};
    const std::vector<VertexId> set = close_to_disc(tin, interior_in_disc(tin, c, 0.1));
    ASSERT_GT(set.size(), 100u);
    for (VertexId v : set)
        ASSERT_FALSE(on_domain_border(tin.domain(), tin.position(v)));
    const std::size_t n = tin.vertex_count();
    const double v0 = tin.volume();
    EditReport report;
    ASSERT_TRUE(tin.remove_planar_patch(set, 1e-9, VolumePolicy::Conserve, &report));
    for (VertexId v : set)
        EXPECT_FALSE(tin.is_alive(v));
    EXPECT_EQ(tin.vertex_count(), n - set.size());
    EXPECT_EQ(report.vertices_removed, set.size());
    EXPECT_TRUE(mesh_is_sound(tin));
    EXPECT_NEAR(tin.volume(), v0, 1e-12);
    EXPECT_NEAR(tin.volume(), test::brute_force_volume(tin), 1e-12);
    LocateHint hint;
    for (Vec2 p : test::random_points_in(Rect{{0.35, 0.35}, {0.65, 0.65}}, 2000, 5))
        EXPECT_NEAR(*tin.height_at(p, &hint), kSlope(p), 1e-12);
    EXPECT_EQ(count_in_disc(tin, c, 0.1), 0u);
    // Removing a disc of vertices on curved sand within a generous tolerance works too.
    Tin curved = Tin::random_points(test::kUnitSquare, 5000, 342, test::rolling_sand);
    const std::vector<VertexId> small = close_to_disc(curved, interior_in_disc(curved, c, 0.03));
    const double cv0 = curved.volume();
    ASSERT_TRUE(curved.remove_planar_patch(small, 0.01));
    EXPECT_NEAR(curved.volume(), cv0, 1e-12);  // Conserve
    EXPECT_TRUE(mesh_is_sound(curved));
}

TEST(Simplifier, PlanarPatchRefusesAndChangesNothing) {
    const Vec2 c{0.5, 0.5};
    auto expect_refused = [](Tin& tin, const std::vector<VertexId>& set, double tol,
                             const char* what) {
        SCOPED_TRACE(what);
        const test::TinState before = test::capture(tin);
        EXPECT_FALSE(tin.remove_planar_patch(set, tol));
        test::expect_snapshots_equal(before.snapshot, tin.snapshot());
        EXPECT_TRUE(tin.check_valid().ok());
    };
    {  // Not planar: one vertex 1 cm off the plane.
        Tin tin = Tin::random_points(test::kUnitSquare, 5000, 351, kSlope);
        const std::vector<VertexId> set = interior_in_disc(tin, c, 0.1);
        tin.set_height(set[set.size() / 2], tin.height(set[set.size() / 2]) + 0.01);
        expect_refused(tin, set, 1e-3, "non-planar");
    }
    {  // A constrained vertex in the set.
        Tin tin = Tin::random_points(test::kUnitSquare, 5000, 352, kSlope);
        std::vector<VertexId> set = interior_in_disc(tin, c, 0.1);
        const std::vector<VertexId> ids =
            tin.insert_points(std::vector<Vec2>{{0.48, 0.5}, {0.52, 0.51}},
                              std::vector<double>{kSlope({0.48, 0.5}), kSlope({0.52, 0.51})});
        tin.insert_constraint(ids[0], ids[1], 1);
        set = interior_in_disc(tin, c, 0.1);
        ASSERT_NE(std::find(set.begin(), set.end(), ids[0]), set.end());
        expect_refused(tin, set, 1e-9, "constrained vertex");
    }
    {  // A ring around a vertex it does not remove (the nearest to the centre).
        Tin tin = Tin::random_points(test::kUnitSquare, 5000, 353, kSlope);
        std::vector<VertexId> set = interior_in_disc(tin, c, 0.1);
        const auto nearest = std::min_element(set.begin(), set.end(), [&](VertexId a, VertexId b) {
            return distance(tin.position(a), c) < distance(tin.position(b), c);
        });
        set.erase(nearest);
        expect_refused(tin, set, 1e-9, "ring around one vertex");
        // An annulus around many.
        std::vector<VertexId> annulus;
        for (VertexId v : interior_in_disc(tin, c, 0.1)) {
            if (distance(tin.position(v), c) > 0.05) annulus.push_back(v);
        }
        expect_refused(tin, annulus, 1e-9, "annulus");
    }
    {  // A border vertex in the set.
        Tin tin = test::smooth_terrain(test::kUnitSquare, 2000, 354, kSlope, 0.05);
        std::vector<VertexId> set;
        for (VertexId v : live_ids(tin)) {
            if (distance(tin.position(v), Vec2{0.5, 0.0}) < 0.1) set.push_back(v);
        }
        expect_refused(tin, set, 1e-9, "border vertex");
    }
}

// ---- One simplifier for many runs ------------------------------------------------------------

/// Sets every live vertex within `r` of `c` on the plane (flattened sand to simplify).
std::vector<VertexId> level_disc(Tin& tin, Vec2 c, double r, const test::Plane& plane) {
    std::vector<VertexId> in = interior_in_disc(tin, c, r);
    for (VertexId v : in)
        tin.set_height(v, plane(tin.position(v)));
    return in;
}

/// Points in the disc (c, r), on the plane, inserted in one batch; returns their ids.
std::vector<VertexId> insert_on_plane(Tin& tin, Vec2 c, double r, std::size_t tries,
                                      std::uint64_t seed, const test::Plane& plane) {
    std::vector<Vec2> pts;
    for (Vec2 p : test::random_points_in(Rect{c - Vec2{r, r}, c + Vec2{r, r}}, tries, seed)) {
        if (distance(p, c) < r) pts.push_back(p);
    }
    std::vector<double> hs;
    for (Vec2 p : pts)
        hs.push_back(plane(p));
    return tin.insert_points(pts, hs);
}

/// A sequence of edits and simplifier runs, identical for both terrains; `run` simplifies
/// the given vertices (through a kept or a fresh Simplifier). Ids are recycled at once (no
/// change tracking), so later insertions take ids that earlier runs flagged. Queues are
/// sparse on flat ground: a flag left over from an earlier run would join a recycled vertex
/// that was not queued to a queued neighbour's planar patch, and it would go.
template <class Run>
void edit_and_simplify(Tin& tin, Run&& run) {
    SimplifySettings settings;
    settings.tolerance = 2e-4;
    auto every_third = [&](const std::vector<VertexId>& vs, std::uint32_t rest) {
        std::vector<VertexId> out;
        for (VertexId v : vs) {
            if (tin.is_alive(v) && v.value % 3 == rest) out.push_back(v);
        }
        return out;
    };
    // 1. High ids: dense new points on a plane; a third of them queued (singletons and small
    // groups).
    const test::Plane a{0.02, 0.01, 0.09};
    const Vec2 ca{0.3, 0.35};
    const std::uint32_t first_new = tin.vertex_capacity();
    const std::vector<VertexId> fresh = insert_on_plane(tin, ca, 0.09, 1500, 371, a);
    const std::vector<VertexId> disc_a = level_disc(tin, ca, 0.1, a);
    std::vector<VertexId> queue;
    for (VertexId v : every_third(fresh, 0)) {
        if (v.value >= first_new) queue.push_back(v);
    }
    ASSERT_GT(queue.size(), 200u);
    run(tin, queue, settings);
    // 2. Low ids: a disc of the original points on another plane, with curved sand around it
    // (some candidates there survive the run).
    const std::vector<VertexId> b = level_disc(tin, {0.6, 0.6}, 0.1, {-0.01, 0.03, 0.1});
    ASSERT_GT(b.size(), 100u);
    run(tin, interior_in_disc(tin, {0.6, 0.6}, 0.16), settings);
    // 3. New points on the first plane take the ids freed by the first run; only another third
    // of the old vertices there is queued.
    const std::vector<VertexId> recycled = insert_on_plane(tin, ca, 0.09, 600, 372, a);
    std::size_t reused = 0;
    for (VertexId v : recycled)
        reused += v.value < first_new + fresh.size() ? 1 : 0;
    ASSERT_GT(reused, 50u);
    run(tin, every_third(disc_a, 1), settings);
    // 4. A disc overlapping both on a third plane, all queued.
    level_disc(tin, {0.45, 0.5}, 0.12, {0.015, 0.015, 0.085});
    run(tin, interior_in_disc(tin, {0.45, 0.5}, 0.3), settings);
    // 5. An empty run, then everything on a looser tolerance.
    run(tin, {}, settings);
    settings.tolerance = 1e-3;
    run(tin, live_ids(tin), settings);
}

TEST(Simplifier, OneSimplifierForManyRunsActsAsAFreshOnePerRun) {
    TinOptions options;
    options.track_changes = false;
    Tin kept_tin = Tin::random_points(test::kUnitSquare, 6000, 370, test::rolling_sand, options);
    Tin fresh_tin = Tin::random_points(test::kUnitSquare, 6000, 370, test::rolling_sand, options);
    std::vector<SimplifyReport> kept_reports;
    std::vector<SimplifyReport> fresh_reports;
    Simplifier kept;
    edit_and_simplify(kept_tin, [&](Tin& tin, const std::vector<VertexId>& queue,
                                    const SimplifySettings& settings) {
        kept.enqueue(queue);
        kept_reports.push_back(kept.run(tin, settings));
        EXPECT_EQ(kept.queued(), 0u);
    });
    edit_and_simplify(fresh_tin, [&](Tin& tin, const std::vector<VertexId>& queue,
                                     const SimplifySettings& settings) {
        Simplifier once;
        once.enqueue(queue);
        fresh_reports.push_back(once.run(tin, settings));
    });
    ASSERT_EQ(kept_reports.size(), 6u);
    ASSERT_EQ(fresh_reports.size(), 6u);
    std::size_t removed = 0;
    for (std::size_t k = 0; k < kept_reports.size(); ++k) {
        SCOPED_TRACE("run " + std::to_string(k));
        EXPECT_EQ(kept_reports[k].tested, fresh_reports[k].tested);
        EXPECT_EQ(kept_reports[k].removed, fresh_reports[k].removed);
        EXPECT_EQ(kept_reports[k].volume_change, fresh_reports[k].volume_change);
        removed += kept_reports[k].removed;
    }
    EXPECT_GT(kept_reports[0].removed, 200u) << "the high-id run";
    EXPECT_GT(kept_reports[1].removed, 50u);
    EXPECT_GT(kept_reports[2].removed, 50u);
    EXPECT_GT(kept_reports[3].removed, 50u);
    EXPECT_GT(removed, 1000u);
    EXPECT_TRUE(kept_tin.check_valid().ok()) << kept_tin.check_valid().summary();
    EXPECT_TRUE(mesh_is_sound(kept_tin));
    // The whole terrain, bit for bit: alive flags, positions, heights and every other field.
    const TinSnapshot a = kept_tin.snapshot();
    const TinSnapshot b = fresh_tin.snapshot();
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
        differ += a.vertices.alive[i] != b.vertices.alive[i] ||
                          (a.vertices.alive[i] && a.vertices.height[i] != b.vertices.height[i])
                      ? 1
                      : 0;
    }
    EXPECT_EQ(differ, 0u) << "vertices alive in one terrain only, or at another height";
    test::expect_snapshots_equal(a, b);
}

}  // namespace
}  // namespace sandtin
