// Shallow water by finite volumes on a TIN (water/shallow_water.hpp), against analytic
// solutions from the SWASHES collection (Delestre et al. 2013) on random-point TINs, not
// grids: Ritter's dam break on a dry bed, Stoker's on a wet one, Thacker's planar surface
// oscillating in a paraboloid; and against properties of the equations: a lake at rest over
// any bed stays at rest, the volume is exact, walls hold the water, depths stay >= 0.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "support/scattered_tin.hpp"
#include "support/swashes.hpp"
#include "tin/tin.hpp"
#include "water/shallow_water.hpp"
#include "water/tin_water_mesh.hpp"

namespace sandtin {
namespace {
namespace shallow_water_test {

/// Runs to time `t_end` at the stable step; false if a depth ever went below 0 (the scheme
/// clamps such a depth and counts it: none may need it under the time step).
bool run_until(ShallowWater& w, double t_end) {
    double t = 0.0;
    bool non_negative = true;
    while (t < t_end) {
        const double dt = std::min(w.stable_time_step(), t_end - t);
        if (!std::isfinite(dt)) break;
        non_negative = non_negative && w.step(dt).outflows_limited == 0;
        t += dt;
    }
    return non_negative;
}

/// sum(A |h - exact|) / sum(A exact): the relative L1 error of the depth.
template <class Exact>
double relative_l1(const ShallowWater& w, Exact exact) {
    double error = 0.0, norm = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double a = w.mesh().area[v];
        const double e = exact(w.mesh().position[v]);
        error += a * std::abs(w.depth(v) - e);
        norm += a * e;
    }
    return error / norm;
}

// ---- Dam breaks on a strip 10 m x 0.2 m, the dam at x = 5 m, after 6 s (SWASHES 4.1.1-2).

constexpr double kDam = 5.0, kDamTime = 6.0, kUpstream = 0.005;

double dam_break_error(double spacing, double downstream) {
    const Tin strip = support::scattered_tin(Rect{{0.0, 0.0}, {10.0, 0.2}}, spacing, 21);
    ShallowWater w(water_mesh_of(strip));
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (!(w.mesh().area[v] > 0.0)) continue;
        w.set_state(v, w.mesh().position[v].x < kDam ? kUpstream : downstream);
    }
    const double volume0 = w.volume();
    EXPECT_TRUE(run_until(w, kDamTime));
    EXPECT_NEAR(w.volume(), volume0, 1e-12 * volume0);  // walls all round
    if (downstream == 0.0) {
        return relative_l1(w,
                           [](Vec2 p) { return swashes::ritter(p.x, kDam, kUpstream, kDamTime); });
    }
    return relative_l1(w, [downstream](Vec2 p) {
        return swashes::stoker(p.x, kDam, kUpstream, downstream, kDamTime);
    });
}

TEST(ShallowWater, RittersDamBreakOnADryBed) {
    // The finer levels and the orders over three halvings: sandtin bench water.
    const double coarse = dam_break_error(0.08, 0.0);
    const double fine = dam_break_error(0.04, 0.0);
    std::printf("[ info     ] Ritter L1: %.4f %.4f (8, 4 cm apart), order %.2f\n", coarse, fine,
                std::log2(coarse / fine));
    EXPECT_LE(fine, 0.05);  // 250 cells along the strip
    EXPECT_LT(fine, coarse);
}

TEST(ShallowWater, StokersDamBreakOnAWetBed) {
    // The finer levels and the orders over three halvings: sandtin bench water.
    const double coarse = dam_break_error(0.08, 0.001);
    const double fine = dam_break_error(0.04, 0.001);
    std::printf("[ info     ] Stoker L1: %.4f %.4f (8, 4 cm apart), order %.2f\n", coarse, fine,
                std::log2(coarse / fine));
    EXPECT_LE(fine, 0.05);
    EXPECT_LT(fine, coarse);
}

// ---- Thacker's planar surface in a paraboloid (SWASHES 4.2.2): bed -h0 (1 - r²/a²).

TEST(ShallowWater, ThackersPlanarSurfaceInAParaboloidAfterOnePeriod) {
    const swashes::ThackerPlanar thacker;
    const double period = thacker.period();
    const auto bed = [&](Vec2 p) { return thacker.bed(p); };
    const Tin bowl = support::scattered_tin(Rect{{-1.6, -1.6}, {1.6, 1.6}}, 0.05, 22, bed);
    ShallowWater w(water_mesh_of(bowl));
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const Vec2 p = w.mesh().position[v];
        const double h = thacker.depth(p, 0.0);
        if (h > 0.0 && w.mesh().area[v] > 0.0) w.set_state(v, h, thacker.velocity(0.0));
    }
    const double volume0 = w.volume();
    ASSERT_TRUE(run_until(w, period));
    EXPECT_NEAR(w.volume(), volume0, 1e-12 * volume0);
    const double error = relative_l1(w, [&](Vec2 p) { return thacker.depth(p, period); });
    std::printf("[ info     ] Thacker L1 after one period: %.4f\n", error);
    EXPECT_LE(error, 0.05);
}

// ---- Properties.

double bumpy(Vec2 p) {
    return 0.05 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y) + 0.03 * p.x;
}

TEST(ShallowWater, ALakeAtRestOverABumpyBedStaysAtRest) {
    // Islands stand above the level 0.02 m: dry land beside wet cells.
    const Tin tin = support::scattered_tin(Rect::from_size(1, 1), 0.05, 23, bumpy);
    ShallowWater w(water_mesh_of(tin));
    const double level = 0.02;
    std::size_t dry = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double h = std::max(0.0, level - w.mesh().bed[v]);
        if (w.mesh().area[v] > 0.0) w.set_state(v, h);
        dry += h == 0.0 ? 1 : 0;
    }
    ASSERT_GT(dry, 100u);
    const double dt = w.stable_time_step();
    for (int k = 0; k < 10000; ++k)
        w.step(dt);
    double fastest = 0.0, off_level = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        fastest = std::max(fastest, length(w.velocity(v)));
        if (w.mesh().bed[v] < level) {
            off_level = std::max(off_level, std::abs(w.surface(v) - level));
        } else {
            EXPECT_EQ(w.depth(v), 0.0) << "dry land stays dry";
        }
    }
    EXPECT_LE(fastest, 1e-10);
    EXPECT_LE(off_level, 1e-12);
}

TEST(ShallowWater, WallsHoldTheWaterAndTheVolumeIsExact) {
    // A hump of water thrown at the walls of a closed box over a bumpy bed.
    const Tin tin = support::scattered_tin(Rect::from_size(1, 1), 0.04, 24, bumpy);
    ShallowWater w(water_mesh_of(tin));
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const Vec2 p = w.mesh().position[v];
        const double hump = 0.05 * std::exp(-40.0 * dot(p - Vec2{0.3, 0.6}, p - Vec2{0.3, 0.6}));
        if (w.mesh().area[v] > 0.0) w.set_state(v, hump + 0.01, {1.0, -0.5});
    }
    const double volume0 = w.volume();
    EXPECT_TRUE(run_until(w, 0.5));
    EXPECT_NEAR(w.volume(), volume0, 1e-12 * volume0);
    EXPECT_EQ(w.volume_left(), 0.0);
}

TEST(ShallowWater, AnOpenSideDrainsATiltedPlane) {
    // 1 cm of water on a plane falling to the west (1 in 5); only the west side is open.
    const Tin tin =
        support::scattered_tin(Rect::from_size(1, 1), 0.05, 25, [](Vec2 p) { return 0.2 * p.x; });
    ShallowWaterOptions options;
    options.manning = 0.03;
    ShallowWater w(water_mesh_of(tin), options);
    std::size_t open = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.mesh().area[v] > 0.0) w.set_state(v, 0.01);
        if (w.mesh().position[v].x == 0.0) {
            w.set_open_border(v, true);
            ++open;
        }
    }
    ASSERT_GT(open, 2u);
    const double volume0 = w.volume();
    EXPECT_TRUE(run_until(w, 6.0));
    EXPECT_LT(w.volume(), 0.2 * volume0);
    EXPECT_NEAR(w.volume() + w.volume_left(), volume0, 1e-12 * volume0);
}

TEST(ShallowWater, DryTerrainCostsNothingAndBadInputIsRefused) {
    const Tin tin = Tin::random_points(Rect::from_size(1, 1), 500, 26, bumpy);
    ShallowWater w(water_mesh_of(tin));
    EXPECT_EQ(w.stable_time_step(), std::numeric_limits<double>::infinity());
    EXPECT_EQ(w.step(0.01).pipes_updated, 0u);
    EXPECT_THROW(w.step(0.0), std::invalid_argument);
    EXPECT_THROW(w.set_state(0, -1.0), std::invalid_argument);
    EXPECT_THROW(w.set_state(0, 0.1, {NAN, 0.0}), std::invalid_argument);
    EXPECT_THROW(w.set_state(w.vertex_count(), 0.1), std::invalid_argument);
    ShallowWaterOptions bad;
    bad.courant = 0.8;
    EXPECT_THROW(ShallowWater(water_mesh_of(tin), bad), std::invalid_argument);
}

}  // namespace shallow_water_test
}  // namespace
}  // namespace sandtin
