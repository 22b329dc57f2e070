// Mean curvature of a vertex's star (physics/mean_curvature) against surfaces whose curvature
// is known in closed form: spheres (1/R), cylinders (1/2R), a paraboloid's apex (2a), a plane
// (0), on random Delaunay triangulations and on a symmetric star.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "physics/mean_curvature.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {
namespace {

/// Curvatures of the interior vertices of `tin` within `radius` of the origin.
std::vector<double> curvatures_near_centre(const Tin& tin, double radius) {
    const VertexArrays& va = tin.vertices();
    std::vector<double> out;
    std::vector<VertexId> ids;
    std::vector<Vec3> ring;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || length(Vec3{va.position[v].x, va.position[v].y, 0.0}) > radius)
            continue;
        if (tin.star(VertexId{v}, ids).boundary) continue;
        ring.clear();
        for (VertexId w : ids)
            ring.push_back({va.position[w.value].x, va.position[w.value].y, va.height[w.value]});
        out.push_back(
            mean_curvature_of_star({va.position[v].x, va.position[v].y, va.height[v]}, ring));
    }
    return out;
}

double mean_of(const std::vector<double>& x) {
    double s = 0.0;
    for (double v : x)
        s += v;
    return s / static_cast<double>(x.size());
}

double median_relative_error(std::vector<double> x, double exact) {
    for (double& v : x)
        v = std::abs(v - exact) / std::abs(exact);
    std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
    return x[x.size() / 2];
}

TEST(MeanCurvature, ASphereCapHasOneOverItsRadius) {
    const double r = 2.0;
    const Tin tin = Tin::random_points(Rect{{-0.8, -0.8}, {0.8, 0.8}}, 20000, 3, [r](Vec2 p) {
        return std::sqrt(r * r - p.x * p.x - p.y * p.y);
    });
    const std::vector<double> h = curvatures_near_centre(tin, 0.6);
    ASSERT_GT(h.size(), 5000u);
    EXPECT_NEAR(mean_of(h), 1.0 / r, 0.01 / r);
    EXPECT_LT(median_relative_error(h, 1.0 / r), 0.1);
    EXPECT_GT(*std::min_element(h.begin(), h.end()), 0.0);  // convex everywhere
}

TEST(MeanCurvature, ABowlIsNegativeAndACylinderHasHalfTheSpheres) {
    const double r = 1.5;
    const Tin bowl = Tin::random_points(Rect{{-0.6, -0.6}, {0.6, 0.6}}, 12000, 4, [r](Vec2 p) {
        return -std::sqrt(r * r - p.x * p.x - p.y * p.y);
    });
    EXPECT_NEAR(mean_of(curvatures_near_centre(bowl, 0.45)), -1.0 / r, 0.01 / r);
    const Tin ridge = Tin::random_points(Rect{{-0.6, -0.6}, {0.6, 0.6}}, 12000, 5,
                                         [r](Vec2 p) { return std::sqrt(r * r - p.x * p.x); });
    EXPECT_NEAR(mean_of(curvatures_near_centre(ridge, 0.45)), 0.5 / r, 0.01 / r);
}

TEST(MeanCurvature, APlaneHasNoneToRounding) {
    const Tin tin = Tin::random_points(Rect::from_size(1, 1), 4000, 6,
                                       [](Vec2 p) { return 0.3 + 0.7 * p.x - 0.4 * p.y; });
    for (double h : curvatures_near_centre(tin, 10.0))
        EXPECT_LT(std::abs(h), 1e-9);
}

TEST(MeanCurvature, ASymmetricStarOnAParaboloidGivesItsApexCurvature) {
    // z = a r²: both principal curvatures 2a at the apex, concave (a valley): H = -2a. On a
    // regular star the estimate is exact for any valence up to the surface's tilt across it,
    // (a rho)²; a barycentric area would give -1.5 a / cos²(pi/n): right only for n = 6.
    const double a = 3.0;
    for (const int n : {5, 6, 9}) {
        for (const double rho : {1e-2, 1e-3}) {
            std::vector<Vec3> ring;
            for (int k = 0; k < n; ++k) {
                const double t = 2.0 * std::numbers::pi * k / n;
                ring.push_back({rho * std::cos(t), rho * std::sin(t), a * rho * rho});
            }
            EXPECT_NEAR(mean_curvature_of_star({0, 0, 0}, ring), -2.0 * a,
                        2.0 * a * 10.0 * (a * rho) * (a * rho))
                << n << " neighbours at " << rho;
        }
    }
}

TEST(MeanCurvature, AStarWithTooFewNeighboursOrNoAreaHasNone) {
    const std::vector<Vec3> two{{1, 0, 1}, {0, 1, 1}};
    EXPECT_EQ(mean_curvature_of_star({0, 0, 0}, two), 0.0);
    const std::vector<Vec3> flat_line{{1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    EXPECT_EQ(mean_curvature_of_star({0, 0, 0}, flat_line), 0.0);
}

}  // namespace
}  // namespace sandtin
