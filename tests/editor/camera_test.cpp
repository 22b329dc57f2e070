// Camera math and picking. Oracles: analytic ray-plane intersections, the matrix path
// (view_projection) against the direct projection, and projection and pixel rays inverting
// each other.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera.hpp"
#include "panel_layout.hpp"
#include "picking.hpp"
#include "tin/tin.hpp"

namespace sandtin::editor {
namespace {

constexpr double kW = 1280.0, kH = 720.0;

std::array<double, 4> apply(const Mat4& m, Vec3 p) {
    std::array<double, 4> r{};
    const double v[4] = {p.x, p.y, p.z, 1.0};
    for (std::size_t row = 0; row < 4; ++row) {
        for (std::size_t col = 0; col < 4; ++col)
            r[row] += static_cast<double>(m[col * 4 + row]) * v[col];
    }
    return r;
}

TEST(Camera, MatrixAgreesWithDirectProjectionAndDepthIsInRange) {
    OrbitCamera c;
    c.target = {0.1, -0.2, 0.05};
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    const Mat4 vp = c.view_projection(kW / kH);
    for (int i = 0; i < 200; ++i) {
        const Vec3 p{u(rng), u(rng), 0.1 * u(rng)};
        double px = 0, py = 0;
        ASSERT_TRUE(c.project(p, kW, kH, px, py));
        const auto clip = apply(vp, p);
        const double nx = clip[0] / clip[3], ny = clip[1] / clip[3], nz = clip[2] / clip[3];
        // Vulkan: x right, y down, depth in [0, 1].
        EXPECT_NEAR((nx + 1.0) * 0.5 * kW, px, 1e-3);
        EXPECT_NEAR((ny + 1.0) * 0.5 * kH, py, 1e-3);
        EXPECT_GT(nz, 0.0);
        EXPECT_LT(nz, 1.0);
    }
}

TEST(Camera, PixelRayPassesThroughTheProjectedPoint) {
    OrbitCamera c;
    c.yaw = 0.7;
    c.pitch = 0.4;
    const Vec3 p{0.2, 0.1, 0.03};
    double px = 0, py = 0;
    ASSERT_TRUE(c.project(p, kW, kH, px, py));
    const Ray r = c.pixel_ray(px, py, kW, kH);
    const Vec3 d = p - r.origin;
    const double t = dot(d, r.direction);
    const Vec3 closest = r.origin + r.direction * t;
    EXPECT_LT(length(p - closest), 1e-9);
    EXPECT_NEAR(length(r.direction), 1.0, 1e-12);
}

TEST(Camera, OrbitClampsPitchZoomScalesAndFrameFitsTheBox) {
    OrbitCamera c;
    c.orbit(0.0, 1e6);
    EXPECT_DOUBLE_EQ(c.pitch, OrbitCamera::kMaxPitch);
    c.orbit(0.0, -1e6);
    EXPECT_DOUBLE_EQ(c.pitch, OrbitCamera::kMinPitch);
    const double d = c.distance;
    c.zoom(2.0);
    EXPECT_NEAR(c.distance, d * 0.88 * 0.88, 1e-12);
    c.zoom(-2.0);
    EXPECT_NEAR(c.distance, d, 1e-12);

    for (double yaw : {0.0, 1.0, 2.5, -2.0}) {
        c.yaw = yaw;
        c.pitch = 0.6;
        const Vec3 lo{-2.0, -1.0, 0.0}, hi{2.0, 1.0, 0.5};
        c.frame(lo, hi);
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
            double px = 0, py = 0;
            ASSERT_TRUE(c.project(corner, kH, kH, px, py));  // square viewport: fits both ways
            EXPECT_GE(px, 0.0);
            EXPECT_LE(px, kH);
            EXPECT_GE(py, 0.0);
            EXPECT_LE(py, kH);
        }
    }
}

TEST(Camera, PanMovesTheTargetWithTheDrag) {
    OrbitCamera c;
    c.yaw = 0.3;
    const Vec3 before = c.target;
    // The point under the target pixel before the pan is seen `dx` pixels to the right after.
    double px0 = 0, py0 = 0;
    ASSERT_TRUE(c.project(before, kW, kH, px0, py0));
    c.pan(40.0, 0.0, kH);
    double px1 = 0, py1 = 0;
    ASSERT_TRUE(c.project(before, kW, kH, px1, py1));
    EXPECT_NEAR(px1 - px0, 40.0, 0.5);
    EXPECT_NEAR(py1 - py0, 0.0, 0.5);
}

// Framing leaves the panel alone: at the window sizes where the terrain used to lie partly
// behind the panel (1024 x 640, 1280 x 800, 1280 x 1000) and at the usual ones, every corner
// of the sandbox's box projects into the part of the window right of the panel, from the
// default angles and from others, and the box still fills most of that part.
TEST(Camera, FrameInPutsEveryCornerOfTheTerrainRightOfThePanel) {
    const Vec3 lo{-0.5, -0.5, 0.0}, hi{0.5, 0.5, 0.1};
    const std::pair<double, double> sizes[] = {
        {1024.0, 640.0}, {1280.0, 800.0}, {1280.0, 1000.0}, {1280.0, 720.0}, {1920.0, 1080.0}};
    for (const auto& [w, h] : sizes) {
        for (double yaw : {-1.9, 0.0, 0.8, 2.5}) {
            for (double pitch : {0.75, 0.3, 1.5}) {
                OrbitCamera c;
                c.yaw = yaw;
                c.pitch = pitch;
                const PixelRect free = free_viewport(w, h);
                ASSERT_TRUE(c.frame_in(lo, hi, w, h, free)) << w << "x" << h;
                PixelRect image{1e300, 1e300, -1e300, -1e300};
                for (int corner = 0; corner < 8; ++corner) {
                    const Vec3 p{(corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                                 (corner & 4) ? hi.z : lo.z};
                    double px = 0.0, py = 0.0;
                    ASSERT_TRUE(c.project(p, w, h, px, py));
                    EXPECT_TRUE(free.contains(px, py))
                        << "corner " << corner << " at (" << px << ", " << py << ") in " << w << "x"
                        << h << ", yaw " << yaw << ", pitch " << pitch;
                    image = {std::min(image.x0, px), std::min(image.y0, py), std::max(image.x1, px),
                             std::max(image.y1, py)};
                }
                EXPECT_GT(std::max(image.width() / free.width(), image.height() / free.height()),
                          0.85)
                    << "the terrain is framed too small in " << w << "x" << h;
            }
        }
    }
}

TEST(Picking, HitsAnAnalyticPlaneWhereTheRayMeetsIt) {
    // z = 0.1 x + 0.05 y + 0.02 on a grid: the TIN is exactly this plane.
    auto plane = [](Vec2 p) { return 0.1 * p.x + 0.05 * p.y + 0.02; };
    const Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 20, 20, plane);
    const Vec2 offset{0.5, 0.5};
    OrbitCamera c;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(200.0, 1000.0), v(150.0, 600.0);
    int hits = 0;
    for (int i = 0; i < 50; ++i) {
        const Ray r = c.pixel_ray(u(rng), v(rng), kW, kH);
        const auto pick = pick_terrain(tin, r, offset, 1e-3, 10.0);
        // Analytic: o + t d on z = a x + b y + c (ray in centre-relative coordinates).
        const double a = 0.1, b = 0.05, cc = 0.02 + 0.1 * offset.x + 0.05 * offset.y;
        const double t = (a * r.origin.x + b * r.origin.y + cc - r.origin.z) /
                         (r.direction.z - a * r.direction.x - b * r.direction.y);
        const Vec3 q = r.origin + r.direction * t;
        const bool inside = std::abs(q.x) <= 0.5 && std::abs(q.y) <= 0.5;
        ASSERT_EQ(pick.has_value(), inside) << i;
        if (!pick) continue;
        ++hits;
        EXPECT_NEAR(pick->point.x, q.x + offset.x, 1e-7);
        EXPECT_NEAR(pick->point.y, q.y + offset.y, 1e-7);
        EXPECT_NEAR(pick->point.z, q.z, 1e-7);
    }
    EXPECT_GT(hits, 10);
}

TEST(Picking, FindsTheFirstCrossingOverARidge) {
    // A ridge along y at x = 0.5: a ray grazing it from the side must stop on the near slope.
    auto ridge = [](Vec2 p) { return 0.2 * std::exp(-std::pow((p.x - 0.5) / 0.05, 2)); };
    const Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 200, 20, ridge);
    const Ray r{{-0.45, 0.0, 0.1}, normalised(Vec3{1.0, 0.0, -0.05})};
    const auto pick = pick_terrain(tin, r, {0.5, 0.5}, 1e-3, 5.0);
    ASSERT_TRUE(pick.has_value());
    EXPECT_LT(pick->point.x, 0.5);  // near side of the ridge
    EXPECT_NEAR(*tin.height_at({pick->point.x, pick->point.y}), pick->point.z, 1e-6);
    // Nothing before it was below the surface.
    for (double t = 0.0; t < pick->distance; t += 1e-3) {
        const Vec3 p = r.origin + r.direction * t;
        EXPECT_GT(p.z, *tin.height_at({p.x + 0.5, p.y + 0.5}) - 1e-9);
    }
}

}  // namespace
}  // namespace sandtin::editor
