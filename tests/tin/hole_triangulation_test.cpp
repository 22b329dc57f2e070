// The hole triangulation (engine/tin/detail): a triangulation of a simple counter-clockwise
// polygon with no added points. Oracles, all re-derived from the polygon and the returned index
// triples: Euler's count n - 2, positive orientation in extended precision, triangle areas
// summing to the shoelace area, every polygon edge used exactly once in its own direction and
// every diagonal exactly twice (once per direction), and every diagonal locally Delaunay (the
// polygon edges are the only constraints). Non-simple and clockwise inputs must give nothing.
// The optional triangle adjacency is checked against the triples alone: the triangle across
// each edge has that edge reversed and names this one back; -1 exactly on the polygon's edges.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "geom/vec2.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/detail/hole_triangulation.hpp"

namespace sandtin {
namespace {

using test::ld;
using test::orient2;
using Triangles = std::vector<std::array<std::size_t, 3>>;

long double shoelace(const std::vector<Vec2>& poly) {
    return test::signed_area_ld(poly);
}

using test::relative_in_circle;

/// Every property a triangulation of the simple CCW polygon must have.
void expect_triangulates(const std::vector<Vec2>& poly, const Triangles& tris) {
    const std::size_t n = poly.size();
    ASSERT_EQ(tris.size(), n - 2);
    long double area = 0.0L;
    // Directed edge (from, to) -> (triangle, corner opposite).
    std::map<std::pair<std::size_t, std::size_t>, std::pair<std::size_t, std::size_t>> directed;
    for (std::size_t k = 0; k < tris.size(); ++k) {
        const auto& t = tris[k];
        for (std::size_t i : t)
            ASSERT_LT(i, n);
        ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) << "triangle " << k;
        const long double a2 = orient2(poly[t[0]], poly[t[1]], poly[t[2]]);
        EXPECT_GT(a2, 0.0L) << "triangle " << k << " is not counter-clockwise with positive area";
        area += a2 / 2.0L;
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t from = t[(i + 1) % 3];
            const std::size_t to = t[(i + 2) % 3];
            EXPECT_TRUE(directed.emplace(std::make_pair(from, to), std::make_pair(k, i)).second)
                << "directed edge " << from << "->" << to << " used twice";
        }
    }
    const long double expected = shoelace(poly);
    EXPECT_LE(std::abs(area - expected), 1e-12L * std::abs(expected))
        << "areas " << static_cast<double>(area) << " vs shoelace "
        << static_cast<double>(expected);
    std::size_t boundary = 0;
    std::size_t diagonal_halves = 0;
    for (const auto& [edge, where] : directed) {
        const auto [from, to] = edge;
        if ((from + 1) % n == to) {
            ++boundary;  // a polygon edge in its own direction
            EXPECT_EQ(directed.count({to, from}), 0u)
                << "polygon edge " << from << "->" << to << " used from outside";
            continue;
        }
        EXPECT_NE((to + 1) % n, from) << "polygon edge " << to << "->" << from << " reversed";
        const auto twin = directed.find({to, from});
        if (twin == directed.end()) {
            ADD_FAILURE() << "diagonal " << from << "->" << to << " has no twin";
            continue;
        }
        ++diagonal_halves;
        // Locally Delaunay: the far corner of the twin triangle is not inside this circumcircle.
        const auto& t = tris[where.first];
        const std::size_t far = tris[twin->second.first][twin->second.second];
        EXPECT_LE(relative_in_circle(poly[t[0]], poly[t[1]], poly[t[2]], poly[far]), 1e-12L)
            << "diagonal " << from << "-" << to << " is not locally Delaunay";
    }
    EXPECT_EQ(boundary, n) << "every polygon edge exactly once";
    EXPECT_EQ(diagonal_halves, 2 * (n - 3)) << "n - 3 diagonals, each used twice";
}

/// A triangle with a long straight side of 201 collinear points and one far apex.
std::vector<Vec2> long_side_fan() {
    std::vector<Vec2> fan;
    for (int k = 0; k <= 200; ++k)
        fan.push_back({k * 0.01, 0.0});
    fan.push_back({1.0, 1e-3});
    return fan;
}

/// An L whose sides are subdivided: collinear runs inside a non-convex polygon.
std::vector<Vec2> subdivided_ell() {
    std::vector<Vec2> ell;
    const std::vector<Vec2> corners = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec2 a = corners[i];
        const Vec2 b = corners[(i + 1) % corners.size()];
        for (int k = 0; k < 8; ++k)
            ell.push_back(a + (b - a) * (k / 8.0));
    }
    return ell;
}

std::vector<Vec2> regular_polygon(std::size_t n, Vec2 centre, double radius, double phase) {
    std::vector<Vec2> p;
    for (std::size_t k = 0; k < n; ++k) {
        const double a =
            phase + 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
        p.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)});
    }
    return p;
}

/// Star-shaped around `centre`: increasing angles (jittered within their sector), random radii.
std::vector<Vec2> random_star(std::size_t n, Vec2 centre, std::uint64_t seed) {
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> jitter(0.05, 0.95);
    std::uniform_real_distribution<double> radius(0.2, 1.0);
    std::vector<Vec2> p;
    for (std::size_t k = 0; k < n; ++k) {
        const double a = 2.0 * std::numbers::pi * (static_cast<double>(k) + jitter(rng)) /
                         static_cast<double>(n);
        const double r = radius(rng);
        p.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a)});
    }
    return p;
}

/// A comb: a base along y = 0 and `teeth` teeth of random heights with narrow gaps, plus
/// `base_points` exactly collinear points along the base. Counter-clockwise.
std::vector<Vec2> comb(int teeth, int base_points, std::uint64_t seed) {
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> height(1.0, 3.0);
    const double width = 0.6;  // tooth width; gaps are 1 - width, floor at y = 0.25
    const double right = static_cast<double>(teeth - 1) + width;
    std::vector<Vec2> p;
    for (int k = 0; k <= base_points; ++k)
        p.push_back({right * k / (base_points + 1), 0.0});
    p.push_back({right, 0.0});
    for (int i = teeth - 1; i >= 0; --i) {
        const double x = static_cast<double>(i);
        const double h = height(rng);
        p.push_back({x + width, h});
        p.push_back({x, h});
        if (i > 0) {
            p.push_back({x, 0.25});
            p.push_back({x - 1.0 + width, 0.25});
        }
    }
    return p;
}

/// The triangle adjacency `neighbours` returns for `tris`, checked against the triples alone:
/// across the edge opposite corner i (from corner i + 1 to corner i + 2) lies a triangle that
/// has the same edge in the other direction and names this triangle back, or -1 exactly where
/// the edge is a polygon edge k -> k + 1. Each polygon edge is -1 once; n - 3 diagonals give
/// 2 (n - 3) interior half-edges.
void expect_adjacency(const std::vector<Vec2>& poly, const Triangles& tris,
                      const std::vector<std::array<int, 3>>& neighbours) {
    const std::size_t n = poly.size();
    ASSERT_EQ(neighbours.size(), tris.size());
    std::vector<int> polygon_edge_seen(n, 0);
    std::size_t interior_halves = 0;
    for (std::size_t t = 0; t < tris.size(); ++t) {
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t from = tris[t][(i + 1) % 3];
            const std::size_t to = tris[t][(i + 2) % 3];
            const int across = neighbours[t][i];
            if (across == -1) {
                EXPECT_EQ((from + 1) % n, to)
                    << "triangle " << t << " corner " << i << ": -1 on the non-polygon edge "
                    << from << "->" << to;
                if (from < n) ++polygon_edge_seen[from];
                continue;
            }
            ASSERT_GE(across, 0) << "triangle " << t << " corner " << i;
            ASSERT_LT(static_cast<std::size_t>(across), tris.size())
                << "triangle " << t << " corner " << i;
            const auto u = static_cast<std::size_t>(across);
            EXPECT_NE(u, t) << "triangle " << t << " is its own neighbour";
            EXPECT_NE((from + 1) % n, to)
                << "polygon edge " << from << "->" << to << " has a triangle outside it";
            ++interior_halves;
            // The shared edge, in the neighbour, runs the other way (both are counter-clockwise).
            std::size_t j = 3;
            for (std::size_t k = 0; k < 3; ++k) {
                if (tris[u][(k + 1) % 3] == to && tris[u][(k + 2) % 3] == from) j = k;
            }
            ASSERT_LT(j, 3u) << "triangle " << u << " (across corner " << i << " of " << t
                             << ") does not have the edge " << to << "->" << from;
            EXPECT_EQ(neighbours[u][j], static_cast<int>(t))
                << "triangle " << u << " does not name " << t << " back across " << to << "-"
                << from;
        }
    }
    for (std::size_t k = 0; k < n; ++k)
        EXPECT_EQ(polygon_edge_seen[k], 1) << "polygon edge " << k << "->" << (k + 1) % n;
    EXPECT_EQ(interior_halves, 2 * (n - 3));
}

/// Triangulates with and without the adjacency: the triangles must be the same, and both must
/// pass their checks. The output vector starts with stale entries, which must not survive.
void expect_triangulates_with_adjacency(const std::vector<Vec2>& poly) {
    const Triangles plain = detail::triangulate_simple_polygon(poly);
    std::vector<std::array<int, 3>> neighbours(poly.size() + 7, std::array<int, 3>{5, -3, 99});
    const Triangles tris = detail::triangulate_simple_polygon(poly, &neighbours);
    EXPECT_EQ(tris, plain) << "the out-parameter changed the triangulation";
    expect_triangulates(poly, tris);
    expect_adjacency(poly, tris, neighbours);
}

/// A band winding `turns` times around `centre`: the outer edge outwards along the spiral
/// r = r0 + growth * angle, then back along the inner edge. Width below the pitch, so the turns
/// never touch. Counter-clockwise; deeply non-convex.
std::vector<Vec2> spiral(double turns, std::size_t points_per_side, Vec2 centre) {
    const double r0 = 0.3;
    const double growth = 0.1;  // pitch 2 pi growth = 0.63
    const double width = 0.35;
    const double end = 2.0 * std::numbers::pi * turns;
    std::vector<Vec2> p;
    auto at = [&](double a, double r) {
        return Vec2{centre.x + r * std::cos(a), centre.y + r * std::sin(a)};
    };
    for (std::size_t k = 0; k < points_per_side; ++k) {
        const double a = end * static_cast<double>(k) / static_cast<double>(points_per_side - 1);
        p.push_back(at(a, r0 + growth * a + width));
    }
    for (std::size_t k = points_per_side; k-- > 0;) {
        const double a = end * static_cast<double>(k) / static_cast<double>(points_per_side - 1);
        p.push_back(at(a, r0 + growth * a));
    }
    return p;
}

TEST(HoleTriangulation, ConvexPolygons) {
    const std::vector<Vec2> triangle = {{0, 0}, {1, 0}, {0, 1}};
    expect_triangulates(triangle, detail::triangulate_simple_polygon(triangle));
    const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    expect_triangulates(square, detail::triangulate_simple_polygon(square));
    // Cocircular: every diagonal choice is Delaunay; still n - 2 proper triangles.
    for (std::size_t n : {5u, 17u, 300u}) {
        SCOPED_TRACE(n);
        const auto poly = regular_polygon(n, {0.31, -0.7}, 0.05, 0.123);
        expect_triangulates(poly, detail::triangulate_simple_polygon(poly));
    }
}

TEST(HoleTriangulation, RandomStarShapedPolygons) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE(seed);
        const auto poly = random_star(100 + 25 * seed, {0.5, 0.25}, seed);
        ASSERT_GT(shoelace(poly), 0.0L);
        expect_triangulates(poly, detail::triangulate_simple_polygon(poly));
    }
}

TEST(HoleTriangulation, CombPolygons) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        SCOPED_TRACE(seed);
        const auto poly = comb(static_cast<int>(20 * seed), static_cast<int>(7 * seed), seed);
        ASSERT_GT(poly.size(), 80u);
        expect_triangulates(poly, detail::triangulate_simple_polygon(poly));
    }
}

TEST(HoleTriangulation, CollinearConsecutivePoints) {
    // An integer square with 49 collinear points on each side: no triangle may take three
    // points of one side (zero area).
    std::vector<Vec2> square;
    const int m = 50;
    for (int k = 0; k < m; ++k)
        square.push_back({static_cast<double>(k), 0.0});
    for (int k = 0; k < m; ++k)
        square.push_back({static_cast<double>(m), static_cast<double>(k)});
    for (int k = 0; k < m; ++k)
        square.push_back({static_cast<double>(m - k), static_cast<double>(m)});
    for (int k = 0; k < m; ++k)
        square.push_back({0.0, static_cast<double>(m - k)});
    expect_triangulates(square, detail::triangulate_simple_polygon(square));
    // A triangle with a long straight side and one far apex: the apex sees them all.
    const std::vector<Vec2> fan = long_side_fan();
    expect_triangulates(fan, detail::triangulate_simple_polygon(fan));
    // Collinear runs inside a non-convex polygon: an L whose sides are subdivided.
    const std::vector<Vec2> ell = subdivided_ell();
    expect_triangulates(ell, detail::triangulate_simple_polygon(ell));
}

TEST(HoleTriangulation, RejectsNonSimpleAndClockwise) {
    auto rejected = [](const std::vector<Vec2>& poly, const char* what) {
        SCOPED_TRACE(what);
        EXPECT_TRUE(detail::triangulate_simple_polygon(poly).empty());
    };
    rejected({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, "bow-tie");
    rejected({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, "clockwise square");
    {
        auto poly = random_star(200, {0, 0}, 77);
        std::reverse(poly.begin(), poly.end());
        rejected(poly, "clockwise star");
    }
    rejected({{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}}, "repeated consecutive point");
    rejected({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}, {1, 1}}, "repeated non-consecutive point");
    // Vertex 4 lies on edge 0-1: two quadrilaterals touching at a point of an edge.
    rejected({{0, 0}, {4, 0}, {4, 4}, {3, 4}, {2, 0}, {1, 4}, {0, 4}}, "vertex on another edge");
    // A notch from the left side whose tip touches the right side.
    rejected({{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 2.5}, {4, 2}, {0, 1.5}}, "notch touching");
    rejected({{0, 0}, {1, 0}}, "two points");
    rejected({}, "empty");
    // A comb with one tooth crossing its neighbour.
    auto crossed = comb(10, 3, 5);
    for (Vec2& p : crossed) {
        if (p.y > 0.5 && p.x == 4.0) p.x = 5.3;  // tooth 4's left side leans past tooth 5
    }
    rejected(crossed, "crossing teeth");
}

TEST(HoleTriangulation, AllCollinearIsNotAPolygon) {
    // Zero area: the triangulation of the points is one-dimensional (it used to crash).
    EXPECT_TRUE(
        detail::triangulate_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}}).empty());
    EXPECT_TRUE(detail::triangulate_simple_polygon(
                    std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {1.5, 1.5}})
                    .empty());
}

TEST(HoleTriangulation, AdjacencyOfConvexAndCollinearPolygons) {
    expect_triangulates_with_adjacency({{0, 0}, {1, 0}, {0, 1}});
    expect_triangulates_with_adjacency({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    for (std::size_t n : {5u, 17u, 300u}) {
        SCOPED_TRACE(n);
        expect_triangulates_with_adjacency(regular_polygon(n, {0.31, -0.7}, 0.05, 0.123));
    }
    const std::vector<Vec2> fan = long_side_fan();
    expect_triangulates_with_adjacency(fan);
    const std::vector<Vec2> ell = subdivided_ell();
    expect_triangulates_with_adjacency(ell);
}

TEST(HoleTriangulation, AdjacencyOfStarsCombsAndSpirals) {
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        SCOPED_TRACE(seed);
        expect_triangulates_with_adjacency(random_star(20 + 37 * seed, {0.5, 0.25}, seed + 100));
        expect_triangulates_with_adjacency(
            comb(static_cast<int>(3 + 4 * seed), static_cast<int>(seed % 5), seed));
    }
    for (double turns : {0.6, 1.5, 3.25}) {
        SCOPED_TRACE(turns);
        const auto poly = spiral(turns, 40 + static_cast<std::size_t>(60 * turns), {2.0, -1.0});
        ASSERT_TRUE(test::is_simple(poly));
        ASSERT_GT(shoelace(poly), 0.0L);
        expect_triangulates_with_adjacency(poly);
    }
}

}  // namespace
}  // namespace sandtin
