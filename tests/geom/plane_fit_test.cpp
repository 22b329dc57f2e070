// plane_fit_residual: the largest vertical miss of points from their least-squares plane.
// Oracles: exact planes (miss 0), a symmetric configuration solved by hand, and an independent
// fit by singular value decomposition of the unscaled design matrix.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geom/plane_fit.hpp"
#include "support/plane_oracle.hpp"

namespace sandtin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(PlaneFit, ExactPlanesMissByNothingAtAnyScaleAndOffset) {
    std::mt19937_64 rng(3);
    for (const double size : {1e-3, 1.0, 100.0}) {
        for (const Vec2 offset : {Vec2{0.0, 0.0}, Vec2{5e5, -3e5}}) {
            std::uniform_real_distribution<double> u(-size, size);
            std::vector<Vec2> xy;
            std::vector<double> z;
            for (int i = 0; i < 12; ++i) {
                const Vec2 p = offset + Vec2{u(rng), u(rng)};
                xy.push_back(p);
                z.push_back(0.3 * (p.x - offset.x) - 0.7 * (p.y - offset.y) + 2.0);
            }
            EXPECT_LE(plane_fit_residual(xy, z, xy.front()), 1e-12 * (1.0 + size))
                << size << " " << offset.x;
        }
    }
}

TEST(PlaneFit, ARaisedCentreOfASquareMissesByFourFifths) {
    // Four corners at 0 and the centre at d: by symmetry the plane is level at d / 5, so the
    // centre misses by 4d/5 and the corners by d/5.
    const std::vector<Vec2> xy = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}, {0.5, 0.5}};
    const std::vector<double> z = {0.0, 0.0, 0.0, 0.0, 0.01};
    EXPECT_NEAR(plane_fit_residual(xy, z, {0.5, 0.5}), 0.008, 1e-15);
}

TEST(PlaneFit, MatchesAnIndependentFitIncludingSqueezedSets) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Aspect 1 uses the normal equations; 1e-7 squeezes the set onto a line so that the
    // pivot ratio sends it to QR.
    for (const double aspect : {1.0, 1e-3, 1e-7}) {
        for (int trial = 0; trial < 50; ++trial) {
            std::vector<Vec2> xy;
            std::vector<double> z;
            for (int i = 0; i < 8; ++i) {
                const Vec2 p{u(rng), aspect * u(rng)};
                xy.push_back(p);
                z.push_back(0.05 * std::sin(3.0 * p.x) + 0.02 * p.y / aspect + 0.001 * u(rng));
            }
            const double expected = test::plane_residual_by_svd(xy, z);
            EXPECT_NEAR(plane_fit_residual(xy, z, xy.front()), expected, 1e-9 * expected)
                << "aspect " << aspect << " trial " << trial;
        }
    }
}

TEST(PlaneFit, PointsThatDoNotDetermineAPlane) {
    const std::vector<Vec2> line = {{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}, {3.0, 3.0}};
    const std::vector<double> z = {0.0, 1.0, 0.5, 0.2};
    EXPECT_EQ(plane_fit_residual(line, z, line.front()), kInf);
    const std::vector<Vec2> two = {{0.0, 0.0}, {1.0, 0.0}};
    EXPECT_EQ(plane_fit_residual(two, std::vector<double>{0.0, 1.0}, two.front()), kInf);
    const std::vector<Vec2> tri = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    EXPECT_EQ(plane_fit_residual(tri, std::vector<double>{0.0, 1.0}, tri.front()), kInf);
    const std::vector<Vec2> same = {{2.0, 2.0}, {2.0, 2.0}, {2.0, 2.0}};
    EXPECT_EQ(plane_fit_residual(same, std::vector<double>{0.0, 1.0, 2.0}, same.front()), kInf);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(plane_fit_residual(tri, std::vector<double>{0.0, nan, 1.0}, tri.front()), kInf);
    const std::vector<Vec2> bad = {{0.0, 0.0}, {nan, 0.0}, {0.0, 1.0}};
    EXPECT_EQ(plane_fit_residual(bad, std::vector<double>{0.0, 0.0, 1.0}, bad.front()), kInf);
    // Three points always fit exactly.
    EXPECT_LE(plane_fit_residual(tri, std::vector<double>{0.0, 1.0, 5.0}, tri.front()), 1e-14);
}

}  // namespace
}  // namespace sandtin
