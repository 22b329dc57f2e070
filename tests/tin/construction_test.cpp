// Construction: flat_rectangle, regular_grid, random_points, from_points.
// Oracles: Euler's formula for the triangle count, the exact integral of a plane for the
// volume, brute-force volume and lumped areas from triangles(), brute-force nearest points.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::brute_force_volume;
using test::close_rel;
using test::Plane;

/// Expects `f` to throw std::invalid_argument with a non-empty message containing `keyword`.
template <class F>
void expect_invalid_argument(F&& f, const std::string& keyword) {
    try {
        f();
        ADD_FAILURE() << "no exception (expected std::invalid_argument about '" << keyword << "')";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(keyword), std::string::npos) << "message: " << what;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

TEST(Construction, FlatRectangleIsTwoTrianglesAtConstantHeight) {
    const Rect d{{-3.0, 2.0}, {5.0, 7.5}};
    const Tin tin = Tin::flat_rectangle(d, 1.25);
    EXPECT_EQ(tin.vertex_count(), 4u);
    EXPECT_EQ(tin.triangle_count(), 2u);  // Euler: 2*4 - 4 - 2
    EXPECT_EQ(tin.domain(), d);
    std::vector<Vec2> corners;
    for (VertexId v : test::live_ids(tin)) {
        corners.push_back(tin.position(v));
        EXPECT_EQ(tin.height(v), 1.25);
        EXPECT_TRUE(tin.is_boundary(v));
        EXPECT_FALSE(tin.is_on_constraint(v));
    }
    for (Vec2 c : {d.min, d.max, Vec2{d.min.x, d.max.y}, Vec2{d.max.x, d.min.y}}) {
        EXPECT_NE(std::find(corners.begin(), corners.end(), c), corners.end());
    }
    const double area = d.width() * d.height();
    EXPECT_TRUE(close_rel(tin.volume(), area * 1.25, 1e-14)) << tin.volume();
    EXPECT_TRUE(close_rel(tin.volume(1.25), 0.0, 0.0, 1e-12 * area));
    EXPECT_TRUE(close_rel(tin.volume(-0.75), area * 2.0, 1e-14));
    EXPECT_EQ(tin.constrained_edge_count(), 0u);
    EXPECT_EQ(tin.constraint_count(), 0u);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, RegularGridCountsFollowEulersFormula) {
    for (const auto& [nx, ny] :
         {std::pair{1, 1}, std::pair{3, 2}, std::pair{10, 7}, std::pair{1, 25}}) {
        SCOPED_TRACE(std::to_string(nx) + "x" + std::to_string(ny));
        const Tin tin = Tin::regular_grid(Rect::from_size(3.0, 2.0), nx, ny);
        const std::size_t v = static_cast<std::size_t>((nx + 1) * (ny + 1));
        const std::size_t hull = static_cast<std::size_t>(2 * (nx + ny));
        EXPECT_EQ(tin.vertex_count(), v);
        EXPECT_EQ(test::border_vertex_count(tin), hull);
        EXPECT_EQ(tin.triangle_count(), test::euler_triangle_count(v, hull));
        EXPECT_EQ(tin.triangle_count(), static_cast<std::size_t>(2 * nx * ny));
        // Without a height function the terrain is flat at 0.
        for (VertexId id : test::live_ids(tin))
            EXPECT_EQ(tin.height(id), 0.0);
        EXPECT_EQ(tin.volume(), 0.0);
        EXPECT_TRUE(test::tin_is_sound(tin));
    }
}

TEST(Construction, RegularGridVerticesSitOnTheGrid) {
    const Rect d{{1.0, -2.0}, {4.0, 2.0}};
    const int nx = 6;
    const int ny = 8;
    const Tin tin = Tin::regular_grid(d, nx, ny);
    std::set<std::pair<int, int>> seen;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        const double fi = (p.x - d.min.x) / d.width() * nx;
        const double fj = (p.y - d.min.y) / d.height() * ny;
        const long i = std::lround(fi);
        const long j = std::lround(fj);
        EXPECT_NEAR(fi, static_cast<double>(i), 1e-9);
        EXPECT_NEAR(fj, static_cast<double>(j), 1e-9);
        seen.insert({static_cast<int>(i), static_cast<int>(j)});
    }
    EXPECT_EQ(seen.size(), static_cast<std::size_t>((nx + 1) * (ny + 1)));
    // Every triangle of a grid has half a cell's area.
    const double half_cell = d.width() / nx * d.height() / ny / 2.0;
    for (const auto& t : tin.triangles()) {
        const double a = static_cast<double>(
            test::orient2(tin.position(t[0]), tin.position(t[1]), tin.position(t[2])) / 2.0L);
        EXPECT_NEAR(a, half_cell, 1e-12 * half_cell);
    }
}

TEST(Construction, PlaneVolumeOnGridIsExactIntegral) {
    const Rect d{{-1.5, 0.25}, {2.5, 3.0}};
    const Plane plane{0.37, -1.21, 4.5};
    const Tin tin = Tin::regular_grid(d, 13, 9, plane);
    for (VertexId v : test::live_ids(tin))
        EXPECT_EQ(tin.height(v), plane(tin.position(v)));
    EXPECT_TRUE(close_rel(tin.volume(), plane.integral(d), 1e-12))
        << tin.volume() << " vs " << plane.integral(d);
    // Datum shifts the volume by datum * area.
    const double area = d.width() * d.height();
    EXPECT_TRUE(close_rel(tin.volume(2.0), plane.integral(d) - 2.0 * area, 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, PlaneVolumeOnRandomPointsIsExactIntegral) {
    const Rect d{{10.0, -4.0}, {17.0, 1.0}};
    const Plane plane{-0.8, 0.45, 12.0};
    for (std::uint64_t seed : {1u, 2u, 99u}) {
        const Tin tin = Tin::random_points(d, 2000, seed, plane);
        EXPECT_TRUE(close_rel(tin.volume(), plane.integral(d), 1e-12))
            << "seed " << seed << ": " << tin.volume() << " vs " << plane.integral(d);
    }
}

TEST(Construction, CurvedVolumeMatchesTriangleByTriangleSum) {
    const Rect d = Rect::from_size(4.0, 3.0);
    auto f = [](Vec2 p) {
        return 1.0 + 0.3 * std::sin(2.0 * p.x) * std::cos(1.3 * p.y) + 0.1 * p.x;
    };
    const Tin tin = Tin::random_points(d, 3000, 5, f);
    EXPECT_TRUE(close_rel(tin.volume(), brute_force_volume(tin), 1e-12))
        << tin.volume() << " vs " << brute_force_volume(tin);
    EXPECT_TRUE(close_rel(tin.volume(0.5), brute_force_volume(tin, 0.5), 1e-12));
    const std::vector<double> lumped = test::brute_force_lumped_areas(tin);
    double sum = 0.0;
    for (VertexId v : test::live_ids(tin)) {
        EXPECT_TRUE(close_rel(tin.vertices().lumped_area[v.index()], lumped[v.index()], 1e-12));
        sum += tin.vertices().lumped_area[v.index()];
    }
    EXPECT_TRUE(close_rel(sum, d.width() * d.height(), 1e-12));
}

TEST(Construction, RandomPointsAreDeterministicAndUseTheHeightFunction) {
    const Rect d = Rect::from_size(5.0, 5.0);
    auto f = [](Vec2 p) { return p.x * p.x - 0.5 * p.y; };
    const Tin a = Tin::random_points(d, 500, 42, f);
    const Tin b = Tin::random_points(d, 500, 42, f);
    const Tin c = Tin::random_points(d, 500, 43, f);
    EXPECT_EQ(a.vertex_count(), 504u);  // corners + points
    EXPECT_EQ(a.triangle_count(), test::euler_triangle_count(504, 4));
    EXPECT_EQ(test::border_vertex_count(a), 4u);
    test::expect_snapshots_equal(a.snapshot(), b.snapshot());
    EXPECT_NE(a.vertices().position, c.vertices().position);
    for (VertexId v : test::live_ids(a)) {
        EXPECT_EQ(a.height(v), f(a.position(v)));
        EXPECT_TRUE(d.contains(a.position(v)));
    }
    EXPECT_TRUE(test::tin_is_sound(a));
}

TEST(Construction, RandomPointsWithoutHeightFunctionAreFlatAtZero) {
    const Tin tin = Tin::random_points(Rect::from_size(2.0, 1.0), 100, 7);
    for (VertexId v : test::live_ids(tin))
        EXPECT_EQ(tin.height(v), 0.0);
    EXPECT_EQ(tin.vertex_count(), 104u);
    EXPECT_EQ(tin.triangle_count(), 2u * 100u + 2u);
}

TEST(Construction, ZeroRandomPointsGiveTheRectangle) {
    const Tin tin = Tin::random_points(Rect::from_size(2.0, 1.0), 0, 7);
    EXPECT_EQ(tin.vertex_count(), 4u);
    EXPECT_EQ(tin.triangle_count(), 2u);
}

TEST(Construction, FromPointsKeepsPositionsAndHeights) {
    const Rect d = Rect::from_size(10.0, 10.0);
    std::mt19937_64 rng = test::test_rng(17);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    std::vector<Vec2> pts;
    std::vector<double> hs;
    for (int i = 0; i < 300; ++i) {
        pts.push_back({u(rng), u(rng)});
        hs.push_back(u(rng) - 5.0);
    }
    const Tin tin = Tin::from_points(d, pts, hs);
    EXPECT_EQ(tin.vertex_count(), 304u);
    std::map<std::pair<double, double>, double> expected;
    for (std::size_t i = 0; i < pts.size(); ++i)
        expected[{pts[i].x, pts[i].y}] = hs[i];
    std::size_t matched = 0;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        const auto it = expected.find({p.x, p.y});
        if (it == expected.end()) continue;
        EXPECT_EQ(tin.height(v), it->second);
        ++matched;
    }
    EXPECT_EQ(matched, pts.size());
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, FromPointsMissingCornersTakeNearestPointHeight) {
    const Rect d{{0.0, 0.0}, {8.0, 6.0}};
    std::mt19937_64 rng = test::test_rng(3);
    std::uniform_real_distribution<double> ux(0.5, 7.5);
    std::uniform_real_distribution<double> uy(0.5, 5.5);
    std::vector<Vec2> pts;
    std::vector<double> hs;
    for (int i = 0; i < 50; ++i) {
        pts.push_back({ux(rng), uy(rng)});
        hs.push_back(static_cast<double>(i) + 0.5);
    }
    // One corner is given explicitly; the other three must be added.
    pts.push_back({8.0, 6.0});
    hs.push_back(-7.0);
    const Tin tin = Tin::from_points(d, pts, hs);
    EXPECT_EQ(tin.vertex_count(), pts.size() + 3);
    for (Vec2 c : {Vec2{0.0, 0.0}, Vec2{8.0, 0.0}, Vec2{0.0, 6.0}, Vec2{8.0, 6.0}}) {
        // Brute-force nearest input point.
        std::size_t best = 0;
        for (std::size_t i = 1; i < pts.size(); ++i) {
            if (length_squared(pts[i] - c) < length_squared(pts[best] - c)) best = i;
        }
        const auto loc = tin.locate(c);
        ASSERT_EQ(loc.kind, Location::Kind::OnVertex) << c.x << "," << c.y;
        double h = test::kNaN;
        for (std::size_t k = 0; k < 3; ++k) {
            if (tin.position(loc.corners[k]) == c) h = tin.height(loc.corners[k]);
        }
        EXPECT_EQ(h, hs[best]) << "corner " << c.x << "," << c.y;
    }
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, FromPointsSingleDuplicateKeepsTheFirstHeight) {
    const std::vector<Vec2> pts = {{1.0, 1.0}, {1.0, 1.0}};
    const std::vector<double> hs = {1.0, 2.0};
    const Tin tin = Tin::from_points(Rect::from_size(10.0, 10.0), pts, hs);
    EXPECT_EQ(tin.vertex_count(), 5u);
    const auto loc = tin.locate({1.0, 1.0});
    ASSERT_EQ(loc.kind, Location::Kind::OnVertex);
    for (VertexId v : loc.corners) {
        if (tin.position(v) == Vec2{1.0, 1.0}) {
            EXPECT_EQ(tin.height(v), 1.0) << "the first of two heights given for (1, 1)";
        }
    }
}

TEST(Construction, FromPointsDuplicatesKeepTheFirstHeight) {
    const Rect d = Rect::from_size(10.0, 10.0);
    std::mt19937_64 rng = test::test_rng(23);
    std::uniform_real_distribution<double> u(0.1, 9.9);
    std::vector<Vec2> unique;
    for (int i = 0; i < 400; ++i)
        unique.push_back({u(rng), u(rng)});
    // Each position appears three times with different heights, in shuffled order.
    std::vector<std::pair<Vec2, double>> items;
    for (std::size_t i = 0; i < unique.size(); ++i) {
        for (int k = 0; k < 3; ++k)
            items.push_back({unique[i], static_cast<double>(i * 10 + static_cast<std::size_t>(k))});
    }
    std::shuffle(items.begin(), items.end(), rng);
    std::vector<Vec2> pts;
    std::vector<double> hs;
    std::map<std::pair<double, double>, double> first;
    for (const auto& [p, h] : items) {
        pts.push_back(p);
        hs.push_back(h);
        first.emplace(std::make_pair(p.x, p.y), h);  // keeps the first occurrence
    }
    const Tin tin = Tin::from_points(d, pts, hs);
    EXPECT_EQ(tin.vertex_count(), unique.size() + 4);
    std::size_t wrong = 0;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        const auto it = first.find({p.x, p.y});
        if (it == first.end()) continue;  // a corner
        if (tin.height(v) != it->second) ++wrong;
    }
    EXPECT_EQ(wrong, 0u) << "vertices whose height is not the first given for their position";
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, FromPointsDuplicateOfACornerKeepsFirstHeight) {
    const Rect d = Rect::from_size(2.0, 2.0);
    const std::vector<Vec2> pts = {{0.0, 0.0}, {1.0, 1.0}, {0.0, 0.0}};
    const std::vector<double> hs = {3.0, 1.0, 9.0};
    const Tin tin = Tin::from_points(d, pts, hs);
    EXPECT_EQ(tin.vertex_count(), 5u);
    const auto loc = tin.locate({0.0, 0.0});
    ASSERT_EQ(loc.kind, Location::Kind::OnVertex);
    for (VertexId v : loc.corners) {
        if (tin.position(v) == Vec2{0.0, 0.0}) {
            EXPECT_EQ(tin.height(v), 3.0);
        }
    }
}

TEST(Construction, FromPointsRejectsBadInput) {
    const Rect d = Rect::from_size(4.0, 4.0);
    const std::vector<Vec2> none;
    const std::vector<double> no_heights;
    expect_invalid_argument([&] { (void)Tin::from_points(d, none, no_heights); }, "no points");

    const std::vector<Vec2> nan_pos = {{1.0, 1.0}, {test::kNaN, 2.0}};
    const std::vector<double> two = {0.0, 0.0};
    expect_invalid_argument([&] { (void)Tin::from_points(d, nan_pos, two); }, "not finite");

    const std::vector<Vec2> inf_pos = {{1.0, 1.0}, {2.0, test::kInf}};
    expect_invalid_argument([&] { (void)Tin::from_points(d, inf_pos, two); }, "not finite");

    const std::vector<Vec2> ok_pos = {{1.0, 1.0}, {2.0, 2.0}};
    const std::vector<double> nan_h = {0.0, test::kNaN};
    expect_invalid_argument([&] { (void)Tin::from_points(d, ok_pos, nan_h); }, "not finite");
    // Finite but beyond the kMaxHeight a terrain may reach (its volume would overflow); the
    // limit itself is fine.
    const std::vector<double> huge_h = {0.0, -1.0000001e9};
    expect_invalid_argument([&] { (void)Tin::from_points(d, ok_pos, huge_h); }, "beyond");
    const std::vector<double> limit_h = {kMaxHeight, -kMaxHeight};
    EXPECT_NO_THROW((void)Tin::from_points(d, ok_pos, limit_h));

    const std::vector<Vec2> outside = {{1.0, 1.0}, {4.0000001, 2.0}};
    expect_invalid_argument([&] { (void)Tin::from_points(d, outside, two); }, "outside");
    const std::vector<Vec2> below = {{1.0, -1e-9}};
    const std::vector<double> one = {0.0};
    expect_invalid_argument([&] { (void)Tin::from_points(d, below, one); }, "outside");

    const std::vector<double> three = {0.0, 0.0, 0.0};
    EXPECT_THROW((void)Tin::from_points(d, ok_pos, three), std::invalid_argument);

    // Points exactly on the border are inside (closed domain).
    const std::vector<Vec2> border = {{0.0, 2.0}, {4.0, 3.0}, {2.0, 4.0}};
    const Tin tin = Tin::from_points(d, border, three);
    EXPECT_EQ(tin.vertex_count(), 7u);
    EXPECT_EQ(test::border_vertex_count(tin), 7u);
    EXPECT_EQ(tin.triangle_count(), test::euler_triangle_count(7, 7));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Construction, RejectsBadDomainsAndSizes) {
    const std::vector<Vec2> pts = {{0.0, 0.0}};
    const std::vector<double> hs = {0.0};
    EXPECT_THROW((void)Tin::from_points(Rect{{0.0, 0.0}, {0.0, 1.0}}, pts, hs),
                 std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {1.0, 0.0}}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {test::kNaN, 1.0}}),
                 std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {test::kInf, 1.0}}),
                 std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect::from_size(1.0, 1.0), test::kNaN),
                 std::invalid_argument);
    EXPECT_THROW((void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 0, 3), std::invalid_argument);
    EXPECT_THROW((void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 3, -1), std::invalid_argument);
    EXPECT_THROW(
        (void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 2, 2, [](Vec2) { return test::kNaN; }),
        std::invalid_argument);
    EXPECT_THROW(
        (void)Tin::random_points(Rect::from_size(1.0, 1.0), 10, 1, [](Vec2) { return test::kInf; }),
        std::invalid_argument);
    EXPECT_THROW((void)Tin::random_points(Rect{}, 10, 1), std::invalid_argument);
}

TEST(Construction, ADomainTooLargeOrTooSmallToComputeIsRefused) {
    // 1e160 m squared overflows an area, 1e-200 m squared underflows one: such terrains were
    // built and saved, then refused when loaded. The limits themselves build sound terrains.
    for (const Rect bad : {Rect::from_size(1e160, 1e160), Rect::from_size(1e-200, 1e-200),
                           Rect::from_size(1e10, 1.0), Rect{{1e13, 0.0}, {1e13 + 1e3, 1.0}}}) {
        try {
            (void)Tin::random_points(bad, 10, 1);
            ADD_FAILURE() << "built a terrain " << bad.width() << " x " << bad.height() << " m";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("sides must lie between 1e-9 m and 1e9 m"),
                      std::string::npos)
                << e.what();
        }
    }
    for (const Rect good : {Rect::from_size(1e-9, 1e-9), Rect::from_size(1e9, 1e9)}) {
        const Tin tin = Tin::random_points(good, 100, 1, [&](Vec2 p) { return p.x * 1e-3; });
        EXPECT_TRUE(test::tin_is_sound(tin)) << good.width();
        EXPECT_TRUE(Tin::from_snapshot(tin.snapshot()).check_valid().ok()) << good.width();
    }
}

TEST(Construction, MoveKeepsTheTerrain) {
    Tin a = Tin::random_points(Rect::from_size(1.0, 1.0), 50, 9, [](Vec2 p) { return p.x; });
    const TinSnapshot before = a.snapshot();
    Tin b = std::move(a);
    test::expect_snapshots_equal(before, b.snapshot());
    Tin c = Tin::flat_rectangle(Rect::from_size(1.0, 1.0));
    c = std::move(b);
    test::expect_snapshots_equal(before, c.snapshot());
    EXPECT_TRUE(c.check_valid().ok());
}

// ---- A fresh build, checked in full -------------------------------------------------------
// The bulk build lays its faces out anew in memory before handing out slots; none of that may
// show. Oracles: distinct input positions, Euler's formula with the border vertices as hull,
// orientation and empty circumcircles in extended precision, and vertex rings re-derived from
// triangles().

/// Checks a freshly built terrain of exactly the positions in `distinct` (corners included).
void expect_fresh_build_sound(const Tin& tin, const std::set<std::pair<double, double>>& distinct,
                              std::uint64_t seed) {
    const ValidationReport r = tin.check_valid();
    ASSERT_TRUE(r.ok()) << r.summary();
    EXPECT_EQ(tin.vertex_count(), distinct.size());
    std::size_t hull = 0;
    for (const auto& [x, y] : distinct)
        hull += test::on_domain_border(tin.domain(), {x, y}) ? 1 : 0;
    EXPECT_EQ(test::border_vertex_count(tin), hull);
    const auto tris = tin.triangles();
    EXPECT_EQ(tris.size(), 2 * distinct.size() - 2 - hull);
    EXPECT_EQ(tin.triangle_count(), tris.size());
    // Slots name the same triangles as triangles().
    std::set<test::Tri> by_slot;
    for (TriangleSlot t = 0; t < tin.slot_capacity(); ++t) {
        const auto tri = tin.slot_triangle(t);
        if (tri[0].valid()) by_slot.insert(test::canonical(tri));
    }
    EXPECT_EQ(by_slot, test::triangle_set(tin));
    // Counter-clockwise, and rings: the neighbours of each vertex, in order, from triangles().
    std::map<VertexId, std::map<VertexId, VertexId>> next_around;  // v -> (a -> b): (v, a, b)
    std::size_t clockwise = 0;
    for (const test::Tri& t : tris) {
        if (!(test::orient2(tin.position(t[0]), tin.position(t[1]), tin.position(t[2])) > 0.0L))
            ++clockwise;
        for (std::size_t i = 0; i < 3; ++i)
            next_around[t[i]][t[(i + 1) % 3]] = t[(i + 2) % 3];
    }
    EXPECT_EQ(clockwise, 0u);
    std::size_t bad_rings = 0;
    std::vector<VertexId> ring;
    for (VertexId v : test::live_ids(tin)) {
        tin.neighbours(v, ring);
        const auto& next = next_around[v];
        std::set<VertexId> expected;
        for (const auto& [a, b] : next) {
            expected.insert(a);
            expected.insert(b);
        }
        bool ok = std::set<VertexId>(ring.begin(), ring.end()) == expected &&
                  ring.size() == expected.size();
        // Consecutive neighbours, cyclically, span a triangle with v, except once on the
        // border, where the ring skips the outside (wherever it starts).
        const bool border = tin.is_boundary(v);
        std::size_t gaps = 0;
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const auto it = next.find(ring[k]);
            gaps += it != next.end() && it->second == ring[(k + 1) % ring.size()] ? 0 : 1;
        }
        ok = ok && gaps == (border ? 1u : 0u);
        bad_rings += ok ? 0 : 1;
        EXPECT_EQ(border, test::on_domain_border(tin.domain(), tin.position(v)));
    }
    EXPECT_EQ(bad_rings, 0u) << "vertices whose neighbours() differ from triangles()";
    // Empty circles: every triangle against its corners' neighbours (which include the far
    // corners of its three neighbours), and a sample against every vertex.
    std::size_t inside = 0;
    for (const test::Tri& t : tris) {
        for (VertexId corner : t) {
            tin.neighbours(corner, ring);
            for (VertexId q : ring) {
                if (q != t[0] && q != t[1] && q != t[2])
                    inside += test::relative_in_circle(tin, t, q) > 1e-12L ? 1 : 0;
            }
        }
    }
    EXPECT_EQ(inside, 0u) << "neighbours inside a triangle's circumcircle";
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
    const std::vector<VertexId> all = test::live_ids(tin);
    std::size_t sample_inside = 0;
    for (int s = 0; s < 60; ++s) {
        const test::Tri& t = tris[pick(rng)];
        for (VertexId q : all) {
            if (q != t[0] && q != t[1] && q != t[2])
                sample_inside += test::relative_in_circle(tin, t, q) > 1e-12L ? 1 : 0;
        }
    }
    EXPECT_EQ(sample_inside, 0u) << "vertices inside a sampled triangle's circumcircle";
}

/// Edits right after the build: insertions, a constraint, single and patch removals.
void expect_fresh_build_edits(Tin& tin, std::uint64_t seed) {
    const Rect d = tin.domain();
    auto valid = [&](const char* after) {
        const ValidationReport r = tin.check_valid();
        EXPECT_TRUE(r.ok()) << after << ": " << r.summary();
        const auto problems = test::mesh_problems(tin);
        EXPECT_TRUE(problems.empty()) << after << ": " << test::join(problems);
    };
    std::mt19937_64 rng = test::test_rng(seed + 1);
    std::uniform_real_distribution<double> ux(d.min.x, d.max.x);
    std::uniform_real_distribution<double> uy(d.min.y, d.max.y);
    std::vector<Vec2> pts;
    for (int k = 0; k < 100; ++k)
        pts.push_back({ux(rng), uy(rng)});
    const std::size_t n0 = tin.vertex_count();
    tin.insert_points(pts, std::vector<double>(pts.size(), 0.5));
    EXPECT_EQ(tin.vertex_count(), n0 + pts.size());
    valid("insert_points");
    const VertexId a = tin.insert_point(d.min + Vec2{0.2 * d.width(), 0.3 * d.height()}, 0.1);
    const VertexId b = tin.insert_point(d.min + Vec2{0.8 * d.width(), 0.6 * d.height()}, 0.2);
    ASSERT_TRUE(tin.insert_constraint(a, b, 1).valid());
    EXPECT_TRUE(tin.is_constrained_edge(a, b) || tin.constrained_edge_count() > 1);
    valid("insert_constraint");
    std::size_t removed = 0;
    for (VertexId v : test::live_ids(tin)) {
        if (v.value % 7 == 3 && !tin.is_boundary(v) && !tin.is_on_constraint(v))
            removed += tin.remove_vertex(v) ? 1 : 0;
    }
    EXPECT_GT(removed, 0u);
    valid("remove_vertex");
    // A patch away from the constraint (which runs from 0.2/0.3 to 0.8/0.6 of the domain).
    std::vector<VertexId> patch;
    const Vec2 c = d.min + Vec2{0.7 * d.width(), 0.2 * d.height()};
    const double r = 0.08 * std::min(d.width(), d.height());
    for (VertexId v : test::live_ids(tin)) {
        if (distance(tin.position(v), c) < r) patch.push_back(v);
    }
    if (patch.size() >= 3 && tin.remove_patch(patch)) {
        for (VertexId v : patch)
            EXPECT_FALSE(tin.is_alive(v));
    }
    valid("remove_patch");
}

TEST(Construction, FreshRandomBuildsAreSoundAndEditable) {
    const Rect d{{-2.0, 1.0}, {3.0, 4.5}};
    for (const auto& [count, seed] :
         {std::pair<std::size_t, std::uint64_t>{1, 801}, {40, 802}, {2500, 803}, {20000, 804}}) {
        SCOPED_TRACE(count);
        Tin tin = Tin::random_points(d, count, seed, [](Vec2 p) { return 0.1 * p.x; });
        std::set<std::pair<double, double>> distinct;
        for (VertexId v : test::live_ids(tin))
            distinct.insert({tin.position(v).x, tin.position(v).y});
        ASSERT_EQ(distinct.size(), count + 4);
        expect_fresh_build_sound(tin, distinct, seed);
        if (count >= 40) expect_fresh_build_edits(tin, seed);
    }
}

TEST(Construction, FreshBuildLaysItsTrianglesOutInVertexOrderAndReportsEverythingOnce) {
    // A bulk build rewrites its triangles in place in the order of their lowest corner id
    // (tin_build.cpp) and hands out slots in that order: the finite triangles' slots come by
    // non-decreasing lowest corner (the faces on the vertex at infinity, which slot_triangle
    // does not show, are keyed by their lowest finite corner among them). The first take
    // reports every vertex and slot (as whole ranges) and the second nothing.
    for (const auto& [count, seed] :
         {std::pair<std::size_t, std::uint64_t>{3, 811}, {500, 812}, {30000, 813}}) {
        SCOPED_TRACE(count);
        Tin tin = Tin::random_points(Rect::from_size(2.0, 1.0), count, seed,
                                     [](Vec2 p) { return 0.2 * p.x * p.y; });
        const ValidationReport report = tin.check_valid();
        ASSERT_TRUE(report.ok()) << report.summary();
        std::uint32_t previous = 0;
        std::size_t finite = 0;
        for (std::uint32_t s = 0; s < tin.slot_capacity(); ++s) {
            const std::array<VertexId, 3> t = tin.slot_triangle(s);
            if (!t[0].valid()) continue;  // a face on the vertex at infinity
            const std::uint32_t lowest = std::min({t[0].value, t[1].value, t[2].value});
            EXPECT_GE(lowest, previous) << "slot " << s;
            previous = lowest;
            ++finite;
        }
        EXPECT_EQ(finite, tin.triangle_count());
        const ChangeSet first = tin.take_changes();
        ASSERT_EQ(first.vertices.size(), 1u);
        EXPECT_EQ(first.vertices[0], (IdRange{0, tin.vertex_capacity()}));
        EXPECT_EQ(tin.vertex_capacity(), count + 4);
        ASSERT_EQ(first.triangles.size(), 1u);
        EXPECT_EQ(first.triangles[0], (IdRange{0, tin.slot_capacity()}));
        EXPECT_TRUE(tin.take_changes().empty());
    }
}

TEST(Construction, FreshBuildsFromPointsWithDuplicatesAndBorderPoints) {
    const Rect d{{0.0, 0.0}, {8.0, 5.0}};
    for (const auto& [count, seed] :
         {std::pair<std::size_t, std::uint64_t>{30, 811}, {3000, 812}, {15000, 813}}) {
        SCOPED_TRACE(count);
        std::mt19937_64 rng = test::test_rng(seed);
        std::uniform_real_distribution<double> ux(d.min.x, d.max.x);
        std::uniform_real_distribution<double> uy(d.min.y, d.max.y);
        std::uniform_int_distribution<int> side(0, 3);
        std::vector<Vec2> pts;
        for (std::size_t k = 0; k < count; ++k)
            pts.push_back({ux(rng), uy(rng)});
        // Points on the border, two corners among them, and duplicates of everything.
        for (std::size_t k = 0; k < count / 10 + 4; ++k) {
            switch (side(rng)) {
                case 0:
                    pts.push_back({ux(rng), d.min.y});
                    break;
                case 1:
                    pts.push_back({ux(rng), d.max.y});
                    break;
                case 2:
                    pts.push_back({d.min.x, uy(rng)});
                    break;
                default:
                    pts.push_back({d.max.x, uy(rng)});
                    break;
            }
        }
        pts.push_back(d.min);
        pts.push_back({d.max.x, d.min.y});
        std::uniform_int_distribution<std::size_t> any(0, pts.size() - 1);
        for (std::size_t k = 0; k < count / 5 + 3; ++k)
            pts.push_back(pts[any(rng)]);
        std::shuffle(pts.begin(), pts.end(), rng);
        std::vector<double> hs;
        for (std::size_t k = 0; k < pts.size(); ++k)
            hs.push_back(0.01 * static_cast<double>(k % 97));
        std::set<std::pair<double, double>> distinct;
        for (Vec2 p : pts)
            distinct.insert({p.x, p.y});
        for (Vec2 c : {d.min, d.max, Vec2{d.min.x, d.max.y}, Vec2{d.max.x, d.min.y}})
            distinct.insert({c.x, c.y});
        ASSERT_LT(distinct.size(), pts.size() + 4) << "the input must hold duplicates";
        Tin tin = Tin::from_points(d, pts, hs);
        expect_fresh_build_sound(tin, distinct, seed);
        expect_fresh_build_edits(tin, seed);
    }
}

TEST(Construction, FreshBuildMatchesIncrementalInsertion) {
    // Random points are in general position, so the Delaunay triangulation is unique: the
    // bulk build and one insertion at a time into the bare rectangle give the same triangles
    // (compared by corner positions, since ids differ).
    const Rect d = Rect::from_size(3.0, 2.0);
    const std::vector<Vec2> pts =
        test::random_points_in(Rect{{0.01, 0.01}, {2.99, 1.99}}, 3000, 821);
    const std::vector<double> hs(pts.size(), 0.0);
    const Tin bulk = Tin::from_points(d, pts, hs);
    Tin incremental = Tin::flat_rectangle(d);
    for (Vec2 p : pts)
        incremental.insert_point(p, 0.0);
    using PositionTri = std::array<std::pair<double, double>, 3>;
    auto by_position = [](const Tin& tin) {
        std::set<PositionTri> out;
        for (const test::Tri& t : tin.triangles()) {
            PositionTri p;
            for (std::size_t i = 0; i < 3; ++i)
                p[i] = {tin.position(t[i]).x, tin.position(t[i]).y};
            // Rotate so the smallest position comes first (keeps the orientation).
            while (!(p[0] < p[1] && p[0] < p[2]))
                p = {p[1], p[2], p[0]};
            out.insert(p);
        }
        return out;
    };
    EXPECT_EQ(bulk.triangle_count(), incremental.triangle_count());
    EXPECT_TRUE(by_position(bulk) == by_position(incremental));
}

}  // namespace
}  // namespace sandtin
