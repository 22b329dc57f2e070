// locate, height_at and neighbours, against brute force over triangles().

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::Tri;

double hills(Vec2 p) {
    return 1.0 + std::sin(p.x) * std::cos(0.8 * p.y);
}

/// True when `t` is `u` up to rotation (same orientation).
bool same_triangle(const Tri& t, const Tri& u) {
    return test::canonical(t) == test::canonical(u);
}

/// Checks one location against brute force: the slot holds the reported corners, the corners
/// form a triangle of the mesh containing p, the weights are a partition of unity and
/// reconstruct p, and the kind matches the weights.
void check_location(const Tin& tin, Vec2 p, const Location& loc) {
    ASSERT_TRUE(loc.inside()) << p.x << "," << p.y;
    ASSERT_NE(loc.slot, kNoSlot);
    EXPECT_TRUE(same_triangle(tin.slot_triangle(loc.slot), loc.corners));
    const auto containing = test::triangles_containing(tin, p);
    ASSERT_FALSE(containing.empty());
    bool member = false;
    for (const Tri& t : containing)
        member = member || same_triangle(t, loc.corners);
    EXPECT_TRUE(member) << "located triangle does not contain " << p.x << "," << p.y;
    double sum = 0.0;
    Vec2 q{0.0, 0.0};
    int zero_weights = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_GE(loc.barycentric[i], 0.0);
        EXPECT_LE(loc.barycentric[i], 1.0);
        sum += loc.barycentric[i];
        q += tin.position(loc.corners[i]) * loc.barycentric[i];
        zero_weights += loc.barycentric[i] < 1e-12 ? 1 : 0;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    const double scale = 1.0 + std::abs(p.x) + std::abs(p.y);
    EXPECT_NEAR(q.x, p.x, 1e-12 * scale);
    EXPECT_NEAR(q.y, p.y, 1e-12 * scale);
    // The kind, from brute force: on a vertex, on an edge (two triangles or the border), inside.
    bool at_vertex = false;
    for (VertexId v : loc.corners)
        at_vertex = at_vertex || tin.position(v) == p;
    if (at_vertex) {
        EXPECT_EQ(loc.kind, Location::Kind::OnVertex);
        EXPECT_EQ(zero_weights, 2);
    } else if (zero_weights == 1) {
        EXPECT_EQ(loc.kind, Location::Kind::OnEdge);
    } else if (containing.size() == 1) {
        EXPECT_EQ(loc.kind, Location::Kind::InTriangle);
    }
}

TEST(Locate, RandomQueriesAgreeWithBruteForce) {
    const Tin tin = Tin::random_points(Rect{{-2.0, 1.0}, {3.0, 5.0}}, 400, 1, hills);
    std::mt19937_64 rng = test::test_rng(1);
    std::uniform_real_distribution<double> ux(-2.0, 3.0);
    std::uniform_real_distribution<double> uy(1.0, 5.0);
    LocateHint hint;
    for (int i = 0; i < 400; ++i) {
        const Vec2 p{ux(rng), uy(rng)};
        const Location plain = tin.locate(p);
        check_location(tin, p, plain);
        EXPECT_EQ(plain.kind, Location::Kind::InTriangle);
        const Location hinted = tin.locate(p, &hint);
        check_location(tin, p, hinted);
        // Strictly inside one triangle: both must find that very triangle.
        EXPECT_EQ(hinted.slot, plain.slot);
        EXPECT_TRUE(tin.is_alive(hint.vertex));
        bool hint_is_corner = false;
        for (VertexId v : hinted.corners)
            hint_is_corner = hint_is_corner || v == hint.vertex;
        EXPECT_TRUE(hint_is_corner) << "hint should move to a vertex of the located triangle";
    }
}

TEST(Locate, VerticesEdgesAndBorderOnAGrid) {
    // Integer grid: edge midpoints are exactly representable, so the kinds are exact.
    const Tin tin = Tin::regular_grid(Rect::from_size(6.0, 4.0), 6, 4, hills);
    LocateHint hint;
    for (int j = 0; j <= 4; ++j) {
        for (int i = 0; i <= 6; ++i) {
            const Vec2 p{static_cast<double>(i), static_cast<double>(j)};
            for (LocateHint* h : {static_cast<LocateHint*>(nullptr), &hint}) {
                const Location loc = tin.locate(p, h);
                check_location(tin, p, loc);
                EXPECT_EQ(loc.kind, Location::Kind::OnVertex);
                // The weight sits entirely on the vertex at p.
                for (std::size_t k = 0; k < 3; ++k) {
                    if (tin.position(loc.corners[k]) == p) {
                        EXPECT_EQ(loc.barycentric[k], 1.0);
                    }
                }
            }
            // Midpoints of the horizontal, vertical and diagonal edges of each cell (whichever
            // diagonal the cell has, its centre lies on it).
            std::vector<Vec2> on_edges;
            if (i < 6) on_edges.push_back({i + 0.5, static_cast<double>(j)});
            if (j < 4) on_edges.push_back({static_cast<double>(i), j + 0.5});
            if (i < 6 && j < 4) on_edges.push_back({i + 0.5, j + 0.5});
            for (Vec2 q : on_edges) {
                for (LocateHint* h : {static_cast<LocateHint*>(nullptr), &hint}) {
                    const Location loc = tin.locate(q, h);
                    check_location(tin, q, loc);
                    EXPECT_EQ(loc.kind, Location::Kind::OnEdge) << q.x << "," << q.y;
                }
            }
        }
    }
}

TEST(Locate, OutsideTheDomain) {
    const Tin tin = Tin::random_points(Rect::from_size(2.0, 2.0), 50, 2, hills);
    LocateHint hint;
    for (Vec2 p : {Vec2{-0.001, 1.0}, Vec2{2.0000001, 1.0}, Vec2{1.0, -5.0}, Vec2{1.0, 2.5},
                   Vec2{100.0, 100.0}, Vec2{test::kNaN, 1.0}, Vec2{1.0, test::kNaN},
                   Vec2{std::numeric_limits<double>::infinity(), 0.0}}) {
        EXPECT_EQ(tin.locate(p).kind, Location::Kind::Outside);
        EXPECT_FALSE(tin.locate(p, &hint).inside());
        EXPECT_FALSE(tin.height_at(p).has_value());
        EXPECT_FALSE(tin.height_at(p, &hint).has_value());
    }
    // The border itself is inside (closed domain).
    for (Vec2 p :
         {Vec2{0.0, 0.7}, Vec2{2.0, 1.3}, Vec2{0.3, 2.0}, Vec2{1.1, 0.0}, Vec2{0.0, 0.0}}) {
        const Location loc = tin.locate(p, &hint);
        check_location(tin, p, loc);
        EXPECT_TRUE(tin.height_at(p).has_value());
    }
}

TEST(Locate, DeadHintIsIgnored) {
    Tin tin = Tin::random_points(Rect::from_size(2.0, 2.0), 100, 3, hills);
    const VertexId v = tin.insert_point({1.0, 1.0}, 0.0);
    LocateHint hint{v};
    ASSERT_TRUE(tin.remove_vertex(v));
    const Vec2 p{1.3, 0.4};
    const Location loc = tin.locate(p, &hint);
    check_location(tin, p, loc);
    EXPECT_TRUE(tin.is_alive(hint.vertex));
    LocateHint garbage{VertexId{123456}};
    check_location(tin, p, tin.locate(p, &garbage));
}

TEST(HeightAt, PlanarTerrainGivesThePlane) {
    const test::Plane plane{1.25, -0.5, 3.0};
    const Rect d{{-3.0, -2.0}, {4.0, 6.0}};
    const Tin tin = Tin::random_points(d, 500, 4, plane);
    std::mt19937_64 rng = test::test_rng(4);
    std::uniform_real_distribution<double> ux(d.min.x, d.max.x);
    std::uniform_real_distribution<double> uy(d.min.y, d.max.y);
    LocateHint hint;
    for (int i = 0; i < 1000; ++i) {
        const Vec2 p{ux(rng), uy(rng)};
        const auto h = tin.height_at(p, i % 2 ? &hint : nullptr);
        ASSERT_TRUE(h.has_value());
        EXPECT_NEAR(*h, plane(p), 1e-12 * (1.0 + std::abs(plane(p))));
    }
    for (Vec2 c : {d.min, d.max})
        EXPECT_NEAR(*tin.height_at(c), plane(c), 1e-12 * 10.0);
}

TEST(HeightAt, CurvedTerrainMatchesBruteForceInterpolation) {
    const Tin tin = Tin::random_points(Rect::from_size(5.0, 5.0), 300, 5, hills);
    std::mt19937_64 rng = test::test_rng(5);
    std::uniform_real_distribution<double> u(0.0, 5.0);
    for (int i = 0; i < 300; ++i) {
        const Vec2 p{u(rng), u(rng)};
        EXPECT_NEAR(*tin.height_at(p), test::brute_force_height(tin, p), 1e-12 * 3.0);
    }
    // At a vertex the height is the vertex's (to rounding of the barycentric weights).
    for (VertexId v : test::live_ids(tin)) {
        EXPECT_NEAR(*tin.height_at(tin.position(v)), tin.height(v), 4e-15);
    }
}

TEST(HeightsAt, MatchHeightAtAndNameATriangleHoldingEachPoint) {
    Tin tin = Tin::random_points(Rect::from_size(5.0, 5.0), 2000, 8, hills);
    // Constraints, so the walk between neighbouring queries crosses constrained edges too.
    std::vector<VertexId> ring;
    for (int k = 0; k < 24; ++k) {
        const double a = 2.0 * std::numbers::pi * k / 24;
        ring.push_back(tin.insert_point({2.5 + 1.2 * std::cos(a), 2.5 + 1.2 * std::sin(a)}, 1.0));
    }
    tin.insert_constraint(ring, /*closed=*/true, 1);
    std::vector<Vec2> points;
    for (double y = 0.013; y < 5.0; y += 0.083) {  // a lattice in row order: the intended use
        for (double x = 0.007; x < 5.0; x += 0.071)
            points.push_back({x, y});
    }
    std::mt19937_64 rng = test::test_rng(8);
    std::uniform_real_distribution<double> u(-0.5, 5.5);  // some outside the domain
    for (int i = 0; i < 1000; ++i)
        points.push_back({u(rng), u(rng)});
    const std::size_t strictly_inside = points.size();
    // On vertices and on edges (midpoints), where several triangles hold the point.
    const std::vector<VertexId> live = test::live_ids(tin);
    for (std::size_t i = 0; i < live.size(); i += 4)
        points.push_back(tin.position(live[i]));
    const std::vector<Tri> tris = tin.triangles();
    for (std::size_t i = 0; i < tris.size(); i += 8)
        points.push_back((tin.position(tris[i][0]) + tin.position(tris[i][1])) * 0.5);
    points.push_back({test::kNaN, 1.0});
    points.push_back({5.0, 5.0});  // a corner of the domain
    std::vector<double> heights(points.size());
    std::vector<std::array<VertexId, 3>> corners(points.size());
    LocateHint hint;
    tin.heights_at(points, heights, &hint, corners);
    std::size_t outside = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::optional<double> want = tin.height_at(points[k]);
        if (!want) {
            EXPECT_TRUE(std::isnan(heights[k])) << k;
            EXPECT_FALSE(corners[k][0].valid()) << k;
            ++outside;
            continue;
        }
        // Inside a triangle the located triangle is unique: bit for bit. On an edge or a
        // vertex another triangle holding the point may be used: equal up to rounding.
        if (k < strictly_inside)
            EXPECT_EQ(heights[k], *want) << k;
        else
            EXPECT_NEAR(heights[k], *want, 1e-14) << k;
        bool holds = false;
        for (const Tri& t : test::triangles_containing(tin, points[k]))
            holds = holds || same_triangle(t, corners[k]);
        EXPECT_TRUE(holds) << "point " << k << " was not interpolated in a triangle holding it";
    }
    EXPECT_GT(outside, 100u);
    std::vector<double> too_few(points.size() - 1);
    EXPECT_THROW(tin.heights_at(points, too_few), std::invalid_argument);
    std::vector<std::array<VertexId, 3>> wrong_corners(3);
    EXPECT_THROW(tin.heights_at(points, heights, nullptr, wrong_corners), std::invalid_argument);
    EXPECT_NO_THROW(tin.heights_at({}, {}));  // nothing to do
}

/// Brute-force neighbours: the other corners of all triangles containing v.
std::set<VertexId> brute_force_neighbours(const Tin& tin, VertexId v) {
    std::set<VertexId> out;
    for (const Tri& t : tin.triangles()) {
        if (std::find(t.begin(), t.end(), v) == t.end()) continue;
        for (VertexId w : t) {
            if (w != v) out.insert(w);
        }
    }
    return out;
}

void check_neighbours(const Tin& tin, const std::set<Tri>& tris) {
    std::vector<VertexId> ns;
    for (VertexId v : test::live_ids(tin)) {
        tin.neighbours(v, ns);
        const std::set<VertexId> expected = brute_force_neighbours(tin, v);
        EXPECT_EQ(std::set<VertexId>(ns.begin(), ns.end()), expected) << "vertex " << v.value;
        EXPECT_EQ(ns.size(), expected.size()) << "duplicates in neighbours of " << v.value;
        const bool border = test::on_domain_border(tin.domain(), tin.position(v));
        EXPECT_EQ(tin.is_boundary(v), border);
        // Counter-clockwise: consecutive neighbours (cyclically) span a triangle (v, n_i, n_i+1)
        // of the mesh, which is then counter-clockwise. Interior vertices: every pair; border
        // vertices: all but the one gap over the outside.
        std::size_t non_triangles = 0;
        double turning = 0.0;
        const Vec2 pv = tin.position(v);
        for (std::size_t i = 0; i < ns.size(); ++i) {
            const VertexId a = ns[i];
            const VertexId b = ns[(i + 1) % ns.size()];
            if (!tris.count(test::canonical({v, a, b}))) ++non_triangles;
            const Vec2 da = tin.position(a) - pv;
            const Vec2 db = tin.position(b) - pv;
            turning += std::atan2(cross(da, db), dot(da, db));
        }
        if (!border) {
            EXPECT_EQ(non_triangles, 0u) << "vertex " << v.value << " neighbours not in ccw order";
            EXPECT_NEAR(turning, 2.0 * std::numbers::pi, 1e-9) << "vertex " << v.value;
        } else {
            EXPECT_EQ(non_triangles, 1u) << "border vertex " << v.value;
        }
    }
}

TEST(Neighbours, MatchBruteForceAndAreCounterClockwise) {
    Tin tin = Tin::random_points(Rect::from_size(3.0, 3.0), 300, 6, hills);
    check_neighbours(tin, test::triangle_set(tin));
    // Also after edits.
    std::mt19937_64 rng = test::test_rng(6);
    std::uniform_real_distribution<double> u(0.0, 3.0);
    for (int i = 0; i < 50; ++i)
        tin.insert_point_on_surface({u(rng), u(rng)});
    for (VertexId v : test::live_ids(tin)) {
        if (v.value % 5 == 0) tin.remove_vertex(v);
    }
    check_neighbours(tin, test::triangle_set(tin));
}

TEST(Neighbours, RegularGridDegrees) {
    const Tin tin = Tin::regular_grid(Rect::from_size(4.0, 4.0), 4, 4);
    check_neighbours(tin, test::triangle_set(tin));
    // Each interior grid vertex touches its 4 axis neighbours plus 2..4 diagonal ones.
    std::vector<VertexId> ns;
    for (VertexId v : test::live_ids(tin)) {
        tin.neighbours(v, ns);
        if (!tin.is_boundary(v)) {
            EXPECT_GE(ns.size(), 4u);
            EXPECT_LE(ns.size(), 8u);
        }
    }
}

TEST(Neighbours, DeadVertexThrows) {
    Tin tin = Tin::random_points(Rect::from_size(3.0, 3.0), 20, 7);
    const VertexId v = tin.insert_point({1.5, 1.5}, 0.0);
    ASSERT_TRUE(tin.remove_vertex(v));
    std::vector<VertexId> ns = {VertexId{1}};
    EXPECT_THROW(tin.neighbours(v, ns), std::invalid_argument);
    EXPECT_THROW((void)tin.is_boundary(v), std::invalid_argument);
    EXPECT_THROW((void)tin.is_on_constraint(v), std::invalid_argument);
    EXPECT_FALSE(tin.is_constrained_edge(v, VertexId{0}));
}

}  // namespace
}  // namespace sandtin
