// geom/plane_gradient.hpp: the gradient of the plane through three points, against planes
// known in closed form, and nothing for a triangle without area (or below the ratio asked).

#include "geom/plane_gradient.hpp"

#include <gtest/gtest.h>

#include <optional>

namespace sandtin {
namespace {

TEST(PlaneGradient, RecoversAKnownPlaneFromAnyTriangleOnIt) {
    const auto z = [](double x, double y) { return 1.0 + 0.3 * x - 0.2 * y; };
    const Vec2 corners[][3] = {{{0, 0}, {1, 0}, {0, 1}},
                               {{0.2, 0.7}, {-3.0, 1.1}, {5.0, -2.0}},
                               {{10.0, 10.0}, {10.001, 10.0}, {10.0, 10.003}}};
    for (const auto& t : corners) {
        const std::optional<Vec2> g =
            plane_gradient({t[0].x, t[0].y, z(t[0].x, t[0].y)}, {t[1].x, t[1].y, z(t[1].x, t[1].y)},
                           {t[2].x, t[2].y, z(t[2].x, t[2].y)});
        ASSERT_TRUE(g.has_value());
        EXPECT_NEAR(g->x, 0.3, 1e-9);
        EXPECT_NEAR(g->y, -0.2, 1e-9);
    }
}

TEST(PlaneGradient, NothingForATriangleWithoutAreaOrBelowTheRatio) {
    EXPECT_FALSE(plane_gradient({0, 0, 0}, {1, 1, 1}, {2, 2, 5}).has_value());  // collinear
    EXPECT_FALSE(plane_gradient({0, 0, 0}, {0, 0, 1}, {1, 0, 0}).has_value());  // repeated
    // A sliver: twice its area 1e-13 against its longer edge squared, 1.
    const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0.5, 1e-13, 0};
    EXPECT_TRUE(plane_gradient(a, b, c).has_value());
    EXPECT_FALSE(plane_gradient(a, b, c, 1e-12).has_value());
    EXPECT_TRUE(plane_gradient(a, b, c, 1e-14).has_value());
}

}  // namespace
}  // namespace sandtin
