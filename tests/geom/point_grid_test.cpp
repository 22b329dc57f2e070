// PointGrid: whether any indexed point lies within a radius of a query point. The oracle is a
// scan of every point with the same comparison (length_squared < radius²). Queries are drawn
// over and beyond the points' extent, on the points themselves, at exactly the radius from
// one, and against clustered sets whose spread is far larger than the radius (bigger cells).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geom/point_grid.hpp"
#include "geom/vec2.hpp"

namespace sandtin {
namespace {

bool brute_force(const std::vector<Vec2>& points, Vec2 p, double radius) {
    for (Vec2 q : points) {
        if (length_squared(q - p) < radius * radius) return true;
    }
    return false;
}

TEST(PointGrid, AnswersAsAScanOfEveryPoint) {
    std::mt19937_64 rng(20261130);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t near = 0;
    std::size_t far = 0;
    for (const double radius : {0.001, 0.02, 0.3, 5.0}) {
        for (const std::size_t count : {std::size_t{1}, std::size_t{50}, std::size_t{3000}}) {
            std::vector<Vec2> points;
            for (std::size_t i = 0; i < count; ++i) {
                // Two clusters 100 m apart: with a 1 mm radius the grid's side cap applies.
                const Vec2 base = i % 2 == 0 ? Vec2{-3.0, 2.0} : Vec2{97.0, 2.0};
                points.push_back(base + Vec2{unit(rng), unit(rng)});
            }
            const PointGrid grid(points, radius);
            for (int k = 0; k < 4000; ++k) {
                Vec2 p;
                const double pick = unit(rng);
                if (pick < 0.4) {
                    const Vec2 base = k % 2 == 0 ? Vec2{-3.0, 2.0} : Vec2{97.0, 2.0};
                    p = base + Vec2{1.4 * unit(rng) - 0.2, 1.4 * unit(rng) - 0.2};
                } else if (pick < 0.6) {
                    p = points[k % points.size()];  // on a point
                } else if (pick < 0.8) {
                    const double a = 6.283185307179586 * unit(rng);  // at about the radius
                    p = points[k % points.size()] + Vec2{std::cos(a), std::sin(a)} * radius;
                } else {
                    p = {-10.0 + 120.0 * unit(rng), -5.0 + 15.0 * unit(rng)};
                }
                const bool want = brute_force(points, p, radius);
                ASSERT_EQ(grid.has_near(p), want)
                    << "radius " << radius << ", " << count << " points, query " << k;
                (want ? near : far) += 1;
            }
        }
    }
    EXPECT_GT(near, 10000u);
    EXPECT_GT(far, 10000u);
}

TEST(PointGrid, StrictRadiusNonFiniteInputAndEmptySets) {
    const std::vector<Vec2> points = {{0.0, 0.0}, {1.0, 0.0}};
    const PointGrid grid(points, 0.5);
    EXPECT_TRUE(grid.has_near({0.25, 0.0}));
    EXPECT_FALSE(grid.has_near({0.5, 0.0}));  // exactly the radius from both: not nearer
    EXPECT_TRUE(grid.has_near({std::nextafter(0.5, 1.0), 0.0}));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(grid.has_near({nan, 0.0}));
    EXPECT_FALSE(PointGrid({}, 0.5).has_near({0.0, 0.0}));
    EXPECT_FALSE(PointGrid(points, 0.0).has_near({0.0, 0.0}));
    EXPECT_FALSE(PointGrid(points, nan).has_near({0.0, 0.0}));
    // A non-finite point is left out; the others still count.
    const std::vector<Vec2> with_nan = {{nan, 0.0}, {2.0, 2.0}};
    const PointGrid partial(with_nan, 0.1);
    EXPECT_TRUE(partial.has_near({2.0, 2.05}));
    EXPECT_FALSE(partial.has_near({0.0, 0.0}));
}

}  // namespace
}  // namespace sandtin
