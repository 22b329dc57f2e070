// Construction: flat_rectangle, regular_grid, random_points, from_points.
// Oracles: Euler's formula for the triangle count, the exact integral of a plane for the
// volume, brute-force volume and lumped areas from triangles(), brute-force nearest points.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::brute_force_volume;
using test::close_rel;
using test::Plane;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_sound(const Tin& tin) {
    const ValidationReport r = tin.check_valid();
    EXPECT_TRUE(r.ok()) << r.summary();
    const auto problems = test::mesh_problems(tin);
    EXPECT_TRUE(problems.empty()) << test::join(problems);
    EXPECT_EQ(tin.triangle_count(),
              test::euler_triangle_count(tin.vertex_count(), test::border_vertex_count(tin)));
}

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
    expect_sound(tin);
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
        expect_sound(tin);
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
    expect_sound(tin);
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
    expect_sound(a);
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
    expect_sound(tin);
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
        double h = kNaN;
        for (std::size_t k = 0; k < 3; ++k) {
            if (tin.position(loc.corners[k]) == c) h = tin.height(loc.corners[k]);
        }
        EXPECT_EQ(h, hs[best]) << "corner " << c.x << "," << c.y;
    }
    expect_sound(tin);
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
    expect_sound(tin);
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

    const std::vector<Vec2> nan_pos = {{1.0, 1.0}, {kNaN, 2.0}};
    const std::vector<double> two = {0.0, 0.0};
    expect_invalid_argument([&] { (void)Tin::from_points(d, nan_pos, two); }, "not finite");

    const std::vector<Vec2> inf_pos = {{1.0, 1.0}, {2.0, kInf}};
    expect_invalid_argument([&] { (void)Tin::from_points(d, inf_pos, two); }, "not finite");

    const std::vector<Vec2> ok_pos = {{1.0, 1.0}, {2.0, 2.0}};
    const std::vector<double> nan_h = {0.0, kNaN};
    expect_invalid_argument([&] { (void)Tin::from_points(d, ok_pos, nan_h); }, "not finite");

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
    expect_sound(tin);
}

TEST(Construction, RejectsBadDomainsAndSizes) {
    const std::vector<Vec2> pts = {{0.0, 0.0}};
    const std::vector<double> hs = {0.0};
    EXPECT_THROW((void)Tin::from_points(Rect{{0.0, 0.0}, {0.0, 1.0}}, pts, hs),
                 std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {1.0, 0.0}}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {kNaN, 1.0}}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{{0.0, 0.0}, {kInf, 1.0}}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect{}), std::invalid_argument);
    EXPECT_THROW((void)Tin::flat_rectangle(Rect::from_size(1.0, 1.0), kNaN), std::invalid_argument);
    EXPECT_THROW((void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 0, 3), std::invalid_argument);
    EXPECT_THROW((void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 3, -1), std::invalid_argument);
    EXPECT_THROW(
        (void)Tin::regular_grid(Rect::from_size(1.0, 1.0), 2, 2, [](Vec2) { return kNaN; }),
        std::invalid_argument);
    EXPECT_THROW(
        (void)Tin::random_points(Rect::from_size(1.0, 1.0), 10, 1, [](Vec2) { return kInf; }),
        std::invalid_argument);
    EXPECT_THROW((void)Tin::random_points(Rect{}, 10, 1), std::invalid_argument);
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

}  // namespace
}  // namespace sandtin
