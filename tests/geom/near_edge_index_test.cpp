// NearEdgeIndex: nearest_edge restricted to a reach. Its contract is nearest_edge's answer, bit
// for bit, whenever that edge is nearer than the reach, and a distance of at least the reach
// otherwise; nearest_edge over the whole polygon is the oracle. Points are sampled over the
// whole neighbourhood and densely around the reach, where a cell boundary or a missing edge
// would show, and on vertices, on edges and at NaN.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "geom/near_edge_index.hpp"
#include "geom/polygon.hpp"
#include "geom/vec2.hpp"
#include "support/tool_oracles.hpp"

namespace sandtin {
namespace {

struct Tally {
    std::size_t near = 0;  ///< points with an edge nearer than the reach
    std::size_t far = 0;
};

void expect_same(const std::vector<Vec2>& poly, double reach, const std::vector<Vec2>& points,
                 Tally& tally) {
    const NearEdgeIndex index(poly, reach);
    std::size_t mismatches = 0;
    for (const Vec2 p : points) {
        const NearestEdge want = nearest_edge(p, poly);
        const NearestEdge got = index.nearest_within_reach(p);
        bool ok;
        if (want.distance < reach) {
            ++tally.near;
            ok = got.index == want.index && got.t == want.t && got.distance == want.distance;
        } else {
            ++tally.far;
            ok = !(got.distance < reach);
        }
        if (!ok && ++mismatches <= 5) {
            ADD_FAILURE() << "reach " << reach << ", point (" << p.x << ", " << p.y
                          << "): nearest_edge gives edge " << want.index << " at " << want.distance
                          << ", the index edge " << got.index << " at " << got.distance;
        }
    }
    EXPECT_EQ(mismatches, 0u);
}

std::vector<Vec2> random_points(Vec2 lo, Vec2 hi, int n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> x(lo.x, hi.x), y(lo.y, hi.y);
    std::vector<Vec2> p;
    for (int i = 0; i < n; ++i)
        p.push_back({x(rng), y(rng)});
    return p;
}

/// Points at distance reach * (1 + f) from random points of the polygon's edges, f in
/// [-0.01, 0.01]: they straddle the reach, on both sides of the contour.
std::vector<Vec2> around_the_reach(const std::vector<Vec2>& poly, double reach, int n,
                                   unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<std::size_t> edge(0, poly.size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0), angle(0.0, 2.0 * std::numbers::pi);
    std::vector<Vec2> p;
    for (int i = 0; i < n; ++i) {
        const std::size_t e = edge(rng);
        const Vec2 a = poly[e], b = poly[(e + 1) % poly.size()];
        const Vec2 on = a + (b - a) * unit(rng);
        const double r = reach * (1.0 + 0.02 * (unit(rng) - 0.5));
        const double t = angle(rng);
        p.push_back({on.x + r * std::cos(t), on.y + r * std::sin(t)});
    }
    return p;
}

TEST(NearEdgeIndex, GivesNearestEdgesAnswersWithinTheReach) {
    const std::vector<std::vector<Vec2>> polygons = {
        test::regular_polygon({0.5, 0.5}, 0.05, 24), test::regular_polygon({0.5, 0.5}, 0.05, 400),
        test::densify(test::unit_lambda(), 1), test::densify(test::unit_lambda(), 40)};
    for (const auto& poly : polygons) {
        const Rect box = bounding_box(poly);
        const double side = std::max(box.width(), box.height());
        for (const double reach : {0.001 * side, 0.05 * side, 0.3 * side, 3.0 * side}) {
            Tally tally;
            const Vec2 margin{2.0 * reach, 2.0 * reach};
            expect_same(poly, reach, random_points(box.min - margin, box.max + margin, 4000, 7),
                        tally);
            expect_same(poly, reach, around_the_reach(poly, reach, 4000, 11), tally);
            // On the vertices and edge midpoints (distance 0).
            std::vector<Vec2> on;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                on.push_back(poly[i]);
                on.push_back((poly[i] + poly[(i + 1) % poly.size()]) * 0.5);
            }
            expect_same(poly, reach, on, tally);
            // Both answers were exercised.
            EXPECT_GT(tally.near, 1000u) << "reach " << reach;
            if (reach < side) {
                EXPECT_GT(tally.far, 1000u) << "reach " << reach;
            }
        }
    }
}

TEST(NearEdgeIndex, DegenerateInput) {
    // Repeated vertices make zero-length edges; nearest_edge handles them and so must the index.
    std::vector<Vec2> poly = test::regular_polygon({0.0, 0.0}, 1.0, 12);
    poly.insert(poly.begin() + 3, poly[3]);
    poly.insert(poly.begin() + 7, poly[7]);
    Tally tally;
    expect_same(poly, 0.2, random_points({-1.5, -1.5}, {1.5, 1.5}, 4000, 3), tally);
    EXPECT_GT(tally.near, 100u);

    const NearEdgeIndex index(poly, 0.2);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(index.nearest_within_reach({nan, 0.0}).distance < 0.2);
    EXPECT_FALSE(index.nearest_within_reach({1e300, -1e300}).distance < 0.2);

    // No usable grid (a zero or non-finite reach, a non-finite vertex): the whole polygon is
    // searched, so the answer is nearest_edge's everywhere.
    for (const double reach : {0.0, std::numeric_limits<double>::infinity()}) {
        const NearEdgeIndex whole(poly, reach);
        const NearestEdge got = whole.nearest_within_reach({0.3, 0.9});
        const NearestEdge want = nearest_edge({0.3, 0.9}, poly);
        EXPECT_EQ(got.index, want.index);
        EXPECT_EQ(got.distance, want.distance);
    }
    std::vector<Vec2> broken = poly;
    broken[5] = {nan, 0.0};
    const NearEdgeIndex whole(broken, 0.2);
    EXPECT_EQ(whole.nearest_within_reach({0.3, 0.9}).index, nearest_edge({0.3, 0.9}, broken).index);
}

}  // namespace
}  // namespace sandtin
