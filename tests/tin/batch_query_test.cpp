// Batch edits and region queries: insert_points, insert_points_on_surface,
// insert_constraints, release_constraints' released vertices, volume_ledger,
// vertices_in_disc, edges_longer_than and section. Oracles: brute force over live vertices
// and triangles(), sequential single edits, and the measured volume.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "support/random_edits.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::Tri;

double knolls(Vec2 p) {
    return 1.0 + 0.5 * std::sin(1.9 * p.x) * std::cos(1.4 * p.y) + 0.02 * p.y;
}

std::vector<Vec2> random_points(std::uint64_t seed, std::size_t n, const Rect& d) {
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> ux(d.min.x, d.max.x);
    std::uniform_real_distribution<double> uy(d.min.y, d.max.y);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back({ux(rng), uy(rng)});
    return out;
}

/// Triangles as sorted position triples: comparable across two Tins.
std::set<std::array<std::pair<double, double>, 3>> geometric_triangles(const Tin& tin) {
    std::set<std::array<std::pair<double, double>, 3>> out;
    for (const Tri& t : tin.triangles()) {
        std::array<std::pair<double, double>, 3> k;
        for (std::size_t i = 0; i < 3; ++i)
            k[i] = {tin.position(t[i]).x, tin.position(t[i]).y};
        std::sort(k.begin(), k.end());
        out.insert(k);
    }
    return out;
}

TEST(BatchInsert, InsertPointsMatchesSequentialInsertion) {
    const Rect d = Rect::from_size(5.0, 5.0);
    Tin batch = Tin::random_points(d, 200, 1, knolls);
    Tin single = Tin::random_points(d, 200, 1, knolls);
    const std::vector<Vec2> pts = random_points(1, 150, d);
    std::vector<double> hs;
    for (std::size_t i = 0; i < pts.size(); ++i)
        hs.push_back(0.5 + 0.01 * static_cast<double>(i));
    const double before = batch.volume();
    EditReport report;
    const std::vector<VertexId> ids = batch.insert_points(pts, hs, nullptr, &report);
    ASSERT_EQ(ids.size(), pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
        EXPECT_EQ(batch.position(ids[i]), pts[i]);
        EXPECT_EQ(batch.height(ids[i]), hs[i]);
        EXPECT_EQ(single.insert_point(pts[i], hs[i]), ids[i]) << "ids are handed out in order";
    }
    EXPECT_EQ(report.vertices_created, pts.size());
    EXPECT_NEAR(report.volume_change, batch.volume() - before, 1e-12 * before);
    // A Delaunay triangulation of points in general position is unique.
    EXPECT_EQ(geometric_triangles(batch), geometric_triangles(single));
    EXPECT_EQ(batch.vertices().height, single.vertices().height);
    EXPECT_TRUE(test::tin_is_sound(batch));
}

TEST(BatchInsert, InsertPointsRejectsBadInputWithoutChangingAnything) {
    Tin tin = Tin::random_points(Rect::from_size(5.0, 5.0), 50, 2, knolls);
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    const std::vector<Vec2> pts = {{1.0, 1.0}, {9.0, 1.0}};
    const std::vector<double> hs = {1.0, 1.0};
    EXPECT_THROW(tin.insert_points(pts, hs), std::invalid_argument);
    const std::vector<Vec2> ok = {{1.0, 1.0}, {2.0, 1.0}};
    const std::vector<double> bad_h = {1.0, std::nan("")};
    EXPECT_THROW(tin.insert_points(ok, bad_h), std::invalid_argument);
    const std::vector<double> short_h = {1.0};
    EXPECT_THROW(tin.insert_points(ok, short_h), std::invalid_argument);
    EXPECT_THROW(tin.insert_points_on_surface(pts), std::invalid_argument);
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(BatchInsert, InsertPointsOnSurfaceConservesVolumeAndKeepsPlanes) {
    const Rect d = Rect::from_size(6.0, 4.0);
    Tin curved = Tin::random_points(d, 300, 3, knolls);
    const double v0 = curved.volume();
    for (int round = 0; round < 10; ++round) {
        const std::vector<Vec2> pts = random_points(100 + static_cast<std::uint64_t>(round), 40, d);
        const std::vector<VertexId> ids = curved.insert_points_on_surface(pts);
        ASSERT_EQ(ids.size(), pts.size());
        for (std::size_t i = 0; i < ids.size(); ++i)
            EXPECT_EQ(curved.position(ids[i]), pts[i]);
        EXPECT_LE(std::abs(curved.volume() - v0), 1e-12 * v0) << "round " << round;
    }
    EXPECT_TRUE(test::tin_is_sound(curved));

    const test::Plane plane{0.3, -0.2, 2.0};
    Tin flat = Tin::random_points(d, 100, 4, plane);
    const std::vector<Vec2> pts = random_points(5, 200, d);
    const std::vector<VertexId> ids = flat.insert_points_on_surface(pts);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        EXPECT_NEAR(flat.height(ids[i]), plane(pts[i]), 1e-12 * 4.0);
    }
    EXPECT_TRUE(test::close_rel(flat.volume(), plane.integral(d), 1e-12));
}

TEST(BatchInsert, ReportPolicyReportsMeasuredChange) {
    const Rect d = Rect::from_size(6.0, 4.0);
    Tin tin = Tin::random_points(d, 300, 6, knolls);
    const double before = tin.volume();
    EditReport report;
    tin.insert_points_on_surface(random_points(6, 100, d), nullptr, VolumePolicy::Report, &report);
    EXPECT_NEAR(report.volume_change, tin.volume() - before, 1e-12 * before);
    EXPECT_EQ(report.vertices_created, 100u);
}

TEST(BatchConstraints, EachSegmentIsItsOwnConstraint) {
    Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 200, 7, knolls);
    std::vector<VertexId> v;
    for (Vec2 p :
         {Vec2{1.0, 1.0}, Vec2{3.0, 1.5}, Vec2{5.0, 1.2}, Vec2{7.0, 1.7}, Vec2{2.0, 6.0},
          Vec2{8.0, 6.0}, Vec2{5.0, 3.0}, Vec2{5.0, 9.0}, Vec2{8.5, 8.2}, Vec2{9.5, 9.4}}) {
        v.push_back(tin.insert_point(p, 1.0));
    }
    // A rim of three segments, one degenerate segment, two segments crossing each other, and
    // one apart.
    const std::vector<std::array<VertexId, 2>> segments = {{v[0], v[1]}, {v[1], v[2]}, {v[2], v[3]},
                                                           {v[3], v[3]}, {v[4], v[5]}, {v[6], v[7]},
                                                           {v[8], v[9]}};
    const auto before = test::live_ids(tin);
    const double v0 = tin.volume();
    EditReport report;
    const std::vector<ConstraintId> ids =
        tin.insert_constraints(segments, 9, VolumePolicy::Conserve, &report);
    ASSERT_EQ(ids.size(), segments.size());
    EXPECT_FALSE(ids[3].valid());
    std::set<ConstraintId> distinct;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (i == 3) continue;
        ASSERT_TRUE(ids[i].valid()) << i;
        distinct.insert(ids[i]);
        const auto info = tin.constraint(ids[i]);
        ASSERT_TRUE(info.has_value());
        EXPECT_EQ(info->generation, 9u);
        EXPECT_EQ(info->vertices.front(), segments[i][0]);
        EXPECT_EQ(info->vertices.back(), segments[i][1]);
    }
    EXPECT_EQ(distinct.size(), 6u);
    EXPECT_EQ(tin.constraint_count(), 6u);
    for (std::size_t i : {0u, 1u, 2u})
        EXPECT_TRUE(tin.is_constrained_edge(segments[i][0], segments[i][1]));
    // The crossing of (2,6)-(8,6) and (5,3)-(5,9) is at (5,6), both segments at height 1 there.
    EXPECT_EQ(report.vertices_created, 1u);
    EXPECT_EQ(tin.vertex_count(), before.size() + 1);
    const Location at = tin.locate({5.0, 6.0});
    EXPECT_EQ(at.kind, Location::Kind::OnVertex);
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    EXPECT_EQ(tin.constrained_edge_count(), 3u + 4u + 1u);
    // Releasing by polygon reports the released vertices.
    const std::vector<Vec2> corner_box = {{8.0, 8.0}, {10.0, 8.0}, {10.0, 10.0}, {8.0, 10.0}};
    ReleaseFilter f;
    f.touching_polygon = corner_box;
    std::vector<VertexId> released;
    EXPECT_EQ(tin.release_constraints(f, VolumePolicy::Conserve, nullptr, &released), 1u);
    EXPECT_FALSE(tin.constraint(ids[6]).has_value());
    EXPECT_EQ(tin.constraint_count(), 5u);
    std::sort(released.begin(), released.end());
    EXPECT_EQ(released, (std::vector<VertexId>{std::min(v[8], v[9]), std::max(v[8], v[9])}));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(VolumeLedger, TracksEveryChangeOfVolume) {
    Tin tin = Tin::random_points(Rect::from_size(8.0, 8.0), 300, 8, knolls);
    const double v0 = tin.volume();
    EXPECT_EQ(tin.volume_ledger(), 0.0);
    test::RandomEditor editor(tin, 8, {.attribute_edits = true, .long_constraint = 0.03});
    for (int op = 1; op <= 1500; ++op) {
        editor.step();
        if (op % 100 == 0) {
            ASSERT_NEAR(tin.volume_ledger(), tin.volume() - v0, 1e-11 * v0) << "op " << op;
        }
    }
    // A height change alone moves the ledger by exactly lumped area times the change.
    const VertexId v = test::live_ids(tin)[17];
    const double before = tin.volume_ledger();
    tin.set_height(v, tin.height(v) + 0.25);
    EXPECT_NEAR(tin.volume_ledger() - before, 0.25 * tin.vertices().lumped_area[v.index()], 1e-14);
}

/// 800 random points over 6 x 4 m with one constraint across the middle, which the region
/// walks must cross (constrained edges do not stop them).
Tin walk_terrain(std::uint64_t seed) {
    Tin tin = Tin::random_points(Rect::from_size(6.0, 4.0), 800, seed, knolls);
    const VertexId a = tin.insert_point({2.0, 2.0}, 1.0);
    const VertexId b = tin.insert_point({4.0, 2.5}, 1.0);
    tin.insert_constraint(a, b, 1);
    return tin;
}

TEST(Queries, VerticesInDiscMatchBruteForce) {
    Tin tin = walk_terrain(9);
    std::mt19937_64 rng = test::test_rng(9);
    std::uniform_real_distribution<double> ux(-1.0, 7.0);
    std::uniform_real_distribution<double> uy(-1.0, 5.0);
    std::uniform_real_distribution<double> ur(0.0, 1.5);
    LocateHint hint;
    for (int k = 0; k < 300; ++k) {
        const Vec2 c = k == 0 ? Vec2{3.0, 2.25} : Vec2{ux(rng), uy(rng)};
        const double r = k == 1 ? 10.0 : ur(rng);
        const auto got_list = tin.vertices_in_disc(c, r, k % 2 ? &hint : nullptr);
        const std::set<VertexId> got(got_list.begin(), got_list.end());
        EXPECT_EQ(got.size(), got_list.size()) << "duplicates";
        for (VertexId v : test::live_ids(tin)) {
            const double dist = distance(tin.position(v), c);
            if (std::abs(dist - r) < 1e-12) continue;  // on the circle: either answer is fine
            EXPECT_EQ(got.count(v) == 1, dist < r)
                << "disc (" << c.x << ", " << c.y << ") r " << r << ", vertex at distance " << dist;
        }
    }
    EXPECT_TRUE(tin.vertices_in_disc({100.0, 100.0}, 1.0).empty());
    EXPECT_EQ(tin.vertices_in_disc({6.0, 4.0}, 0.0).size(), 1u);  // exactly the corner
}

// vertices_in_polygon must find exactly the vertices PolygonInclusion::contains() accepts: the
// brute-force oracle is that test over every live vertex. Polygons: a λ, a 200-edge subdivided
// λ (banded), a comb with teeth narrower than the triangles (necks with no vertex in them,
// which a walk over faces with a corner inside would not cross), polygons partly outside the
// domain and one around it.
TEST(Queries, VerticesInPolygonMatchContainsEverywhere) {
    const Tin tin = walk_terrain(19);
    const std::vector<Vec2> lambda = {{0.0, 0.0}, {0.15, 0.0}, {0.5, 0.4},  {0.85, 0.0},
                                      {1.0, 0.0}, {0.3, 1.0},  {0.15, 1.0}, {0.42, 0.55}};
    auto placed = [](const std::vector<Vec2>& poly, Vec2 at, double scale) {
        std::vector<Vec2> out;
        for (Vec2 p : poly)
            out.push_back(at + p * scale);
        return out;
    };
    auto subdivided = [](const std::vector<Vec2>& poly, int parts) {
        std::vector<Vec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i)
            for (int k = 0; k < parts; ++k)
                out.push_back(poly[i] + (poly[(i + 1) % poly.size()] - poly[i]) *
                                            (static_cast<double>(k) / parts));
        return out;
    };
    // Teeth 0.02 wide, 1.6 tall: far narrower than the ~0.17-spaced vertices.
    std::vector<Vec2> comb = {{0.5, 0.5}, {5.5, 0.5}};
    for (int t = 9; t >= 0; --t) {
        const double x = 0.5 + 0.5 * t;
        comb.insert(comb.end(), {{x + 0.5, 0.6}, {x + 0.5, 3.5}, {x + 0.48, 3.5}, {x + 0.48, 0.6}});
    }
    comb.back() = {0.5, 3.5};
    comb.erase(comb.end() - 2);
    ASSERT_TRUE(is_simple_polygon(comb));
    std::vector<std::vector<Vec2>> polygons = {
        placed(lambda, {2.0, 1.0}, 2.0),
        subdivided(placed(lambda, {1.0, 0.5}, 3.0), 25),
        comb,
        placed(lambda, {4.5, 3.0}, 3.0),                       // partly outside the domain
        {{-1.0, -1.0}, {7.0, -1.0}, {7.0, 5.0}, {-1.0, 5.0}},  // around the domain
        {{-1.0, 1.0}, {7.0, 1.0}, {7.0, 1.3}, {-1.0, 1.3}},    // a band across it
    };
    std::mt19937_64 rng = test::test_rng(19);
    std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
    for (int k = 0; k < 8; ++k) {  // the λ turned about its centre
        std::vector<Vec2> turned;
        const double t = angle(rng);
        for (Vec2 p : placed(lambda, {-0.5, -0.5}, 1.0))
            turned.push_back(Vec2{3.0, 2.0} + rotate(p, t) * 2.5);
        polygons.push_back(turned);
    }
    LocateHint hint;
    for (std::size_t k = 0; k < polygons.size(); ++k) {
        const PolygonInclusion region(polygons[k], polygons[k][0]);
        const auto got_list = tin.vertices_in_polygon(region, k % 2 ? &hint : nullptr);
        const std::set<VertexId> got(got_list.begin(), got_list.end());
        EXPECT_EQ(got.size(), got_list.size()) << "duplicates in polygon " << k;
        std::size_t inside = 0;
        for (VertexId v : test::live_ids(tin)) {
            const bool expected = region.contains(tin.position(v));
            inside += expected ? 1 : 0;
            EXPECT_EQ(got.count(v) == 1, expected) << "polygon " << k << ", vertex " << v.value;
        }
        EXPECT_GT(inside, 0u) << "polygon " << k << " covers no vertex: the case proves nothing";
    }
}

/// Distance from c to the closed triangle.
double distance_to_triangle(Vec2 c, Vec2 p0, Vec2 p1, Vec2 p2) {
    const auto w = test::barycentric(c, p0, p1, p2);
    if (w[0] >= 0.0L && w[1] >= 0.0L && w[2] >= 0.0L) return 0.0;
    return std::min({test::distance_to_segment_ld(c, p0, p1),
                     test::distance_to_segment_ld(c, p1, p2),
                     test::distance_to_segment_ld(c, p2, p0)});
}

TEST(Queries, EdgesLongerThanMatchBruteForce) {
    Tin tin = Tin::random_points(Rect::from_size(6.0, 4.0), 300, 10, knolls);
    std::mt19937_64 rng = test::test_rng(10);
    std::uniform_real_distribution<double> ux(0.0, 6.0);
    std::uniform_real_distribution<double> uy(0.0, 4.0);
    std::uniform_real_distribution<double> ur(0.0, 1.0);
    std::uniform_real_distribution<double> ul(0.05, 0.4);
    const auto tris = tin.triangles();
    for (int k = 0; k < 200; ++k) {
        const Vec2 c{ux(rng), uy(rng)};
        const double r = ur(rng);
        const double max_length = ul(rng);
        std::set<std::pair<VertexId, VertexId>> must, may;
        for (const Tri& t : tris) {
            const double dist =
                distance_to_triangle(c, tin.position(t[0]), tin.position(t[1]), tin.position(t[2]));
            if (dist > r + 1e-9) continue;
            for (int i = 0; i < 3; ++i) {
                VertexId a = t[static_cast<std::size_t>(i)];
                VertexId b = t[static_cast<std::size_t>((i + 1) % 3)];
                if (b < a) std::swap(a, b);
                if (!(distance(tin.position(a), tin.position(b)) > max_length)) continue;
                may.insert({a, b});
                if (dist < r - 1e-9) must.insert({a, b});
            }
        }
        std::set<std::pair<VertexId, VertexId>> got;
        for (const auto& e : tin.edges_longer_than(c, r, max_length)) {
            VertexId a = e[0], b = e[1];
            if (b < a) std::swap(a, b);
            EXPECT_TRUE(got.insert({a, b}).second) << "edge reported twice";
        }
        EXPECT_TRUE(std::includes(got.begin(), got.end(), must.begin(), must.end()))
            << "query " << k;
        EXPECT_TRUE(std::includes(may.begin(), may.end(), got.begin(), got.end())) << "query " << k;
    }
}

TEST(Queries, SectionIsTheSurfaceAlongTheSegment) {
    const Rect d = Rect::from_size(6.0, 4.0);
    Tin tin = Tin::random_points(d, 400, 11, knolls);
    std::mt19937_64 rng = test::test_rng(11);
    std::uniform_real_distribution<double> ux(0.0, 6.0);
    std::uniform_real_distribution<double> uy(0.0, 4.0);
    for (int k = 0; k < 30; ++k) {
        const Vec2 a{ux(rng), uy(rng)};
        const Vec2 b{ux(rng), uy(rng)};
        const auto sec = tin.section(a, b);
        ASSERT_GE(sec.size(), 2u);
        EXPECT_EQ(sec.front().first, 0.0);
        EXPECT_EQ(sec.back().first, 1.0);
        for (std::size_t i = 1; i < sec.size(); ++i)
            ASSERT_LT(sec[i - 1].first, sec[i].first);
        // Every point of the section lies on the surface.
        for (const auto& [t, z] : sec) {
            EXPECT_NEAR(z, test::brute_force_height(tin, lerp(a, b, t)), 1e-9) << "t " << t;
        }
        // And the polyline through them is the surface: no breakpoint is missing.
        std::size_t seg = 0;
        for (int j = 0; j <= 500; ++j) {
            const double t = j / 500.0;
            while (seg + 2 < sec.size() && sec[seg + 1].first < t)
                ++seg;
            const auto& [t0, z0] = sec[seg];
            const auto& [t1, z1] = sec[seg + 1];
            const double z = z0 + (z1 - z0) * (t - t0) / (t1 - t0);
            ASSERT_NEAR(z, test::brute_force_height(tin, lerp(a, b, t)), 1e-9)
                << "query " << k << " t " << t;
        }
        // Every triangle edge crossed by the segment is a breakpoint.
        std::size_t crossings = 0;
        for (const Tri& tri : tin.triangles()) {
            for (int i = 0; i < 3; ++i) {
                const Vec2 p = tin.position(tri[static_cast<std::size_t>(i)]);
                const Vec2 q = tin.position(tri[static_cast<std::size_t>((i + 1) % 3)]);
                const long double o1 = test::orient2(a, b, p), o2 = test::orient2(a, b, q);
                const long double o3 = test::orient2(p, q, a), o4 = test::orient2(p, q, b);
                if (o1 * o2 < 0.0L && o3 * o4 < 0.0L) ++crossings;  // proper crossings, each twice
            }
        }
        EXPECT_GE(sec.size(), 2 + crossings / 2) << "query " << k;
    }
    // Outside points are clamped into the domain.
    const auto clamped = tin.section({-5.0, 2.0}, {3.0, 2.0});
    EXPECT_NEAR(clamped.front().second, *tin.height_at({0.0, 2.0}), 1e-12);
}

}  // namespace
}  // namespace sandtin
