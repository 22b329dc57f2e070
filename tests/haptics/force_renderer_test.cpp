// Interpolation between geometry updates (seed 000 Eq. 7.15), zero out of contact, clamp and
// the stale-snapshot ramp, tick by tick on a synthetic clock.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "haptics/force_renderer.hpp"

namespace sandtin::haptics {
namespace {

constexpr std::int64_t kMs = 1'000'000;

HapticSnapshot flat(double h, std::uint64_t sequence, std::int64_t published_ns) {
    HapticSnapshot s;
    s.sequence = sequence;
    s.published_ns = published_ns;
    s.centre = {0.5, 0.5};
    s.centre_height = h;
    s.control_count = 8;
    for (std::size_t i = 0; i < 8; ++i) {
        const double a = 2.0 * std::numbers::pi * static_cast<double>(i) / 8.0;
        s.control[i] = {0.5 + 0.04 * std::cos(a), 0.5 + 0.04 * std::sin(a)};
        s.control_height[i] = h;
    }
    return s;
}

ForceRendererConfig config() {
    ForceRendererConfig c;
    c.ramp_ns = 1 * kMs;  // full gain after one tick, so the blend is seen unscaled
    return c;
}

TEST(ForceRenderer, BlendsLinearlyBetweenUpdatesLikeEq715) {
    ForceRenderer r(config());
    const Vec3 pen{0.5, 0.5, -0.002};
    // Snapshot 1 at t=0: surface 0, F = 800 (0.002 + 0.000625) = 2.1 N. The first snapshot
    // blends in from zero over first_blend_ticks = 16.
    HapticSnapshot a = flat(0.0, 1, 0);
    std::int64_t t = 0;
    TickOutput o = r.tick(pen, t, &a);
    EXPECT_NEAR(o.force.z, 0.0, 1e-12);  // it = 0: F_old = 0
    for (int it = 1; it < 20; ++it) {
        t += kMs;
        o = r.tick(pen, t, nullptr);
        EXPECT_NEAR(o.force.z, 2.1 * std::min(1.0, it / 16.0), 1e-9) << it;
    }
    // Snapshot 2 after 20 ticks: the surface dropped to -1 mm, F = 800 * 0.001625 = 1.3 N.
    // it_p = 20 (ticks between the two arrivals): F_out = 2.1 + (1.3 - 2.1) it / 20.
    t += kMs;
    HapticSnapshot b = flat(-0.001, 2, t);
    o = r.tick(pen, t, &b);
    EXPECT_NEAR(o.force.z, 2.1, 1e-9);
    for (int it = 1; it <= 25; ++it) {
        t += kMs;
        o = r.tick(pen, t, nullptr);
        EXPECT_NEAR(o.force.z, 2.1 + (1.3 - 2.1) * std::min(1.0, it / 20.0), 1e-9) << it;
    }
}

TEST(ForceRenderer, ZeroOutOfContactAndClamped) {
    ForceRenderer r(config());
    HapticSnapshot s = flat(0.0, 1, 0);
    std::int64_t t = 0;
    r.tick({0.5, 0.5, 0.01}, t, &s);
    for (int i = 0; i < 50; ++i) {
        t += kMs;
        const TickOutput o = r.tick({0.5, 0.5, 0.01}, t, nullptr);
        EXPECT_FALSE(o.contact);
        EXPECT_EQ(o.force, (Vec3{}));
    }
    for (int i = 0; i < 50; ++i) {
        t += kMs;
        const TickOutput o = r.tick({0.5, 0.5, -0.5}, t, nullptr);
        EXPECT_LE(length(o.force), 10.0 + 1e-12);
    }
}

TEST(ForceRenderer, StaleSnapshotRampsDownSmoothlyAndBack) {
    ForceRendererConfig c;
    c.stale_after_ns = 300 * kMs;
    c.ramp_ns = 200 * kMs;
    ForceRenderer r(c);
    const Vec3 pen{0.5, 0.5, -0.01};  // 800 * 0.010625 = 8.5 N
    HapticSnapshot s = flat(0.0, 1, 0);
    std::int64_t t = 0;
    TickOutput o = r.tick(pen, t, &s);
    double previous = length(o.force);
    double max_step = 0.0;
    bool saw_full = false;
    bool saw_zero_after_stale = false;
    for (int i = 1; i < 800; ++i) {
        t += kMs;
        o = r.tick(pen, t, nullptr);
        const double f = length(o.force);
        max_step = std::max(max_step, std::abs(f - previous));
        if (std::abs(f - 8.5) < 1e-9) saw_full = true;
        EXPECT_EQ(o.stale, t > 300 * kMs) << i;
        if (t > 300 * kMs) {
            EXPECT_LE(f, previous + 1e-12) << i;  // never rises while stale
        }
        if (o.stale && f == 0.0) saw_zero_after_stale = true;
        previous = f;
    }
    EXPECT_TRUE(saw_full);
    EXPECT_TRUE(saw_zero_after_stale);
    // 8.5 N over a 200-tick ramp: at most 8.5 / 200 N per tick (plus the initial blend).
    EXPECT_LE(max_step, 8.5 / 16.0 + 1e-9);
    // Snapshots resume: the force comes back up without a jump.
    HapticSnapshot fresh = flat(0.0, 2, t);
    previous = 0.0;
    for (int i = 0; i < 300; ++i) {
        t += kMs;
        fresh.published_ns = t;
        ++fresh.sequence;
        o = r.tick(pen, t, &fresh);
        EXPECT_LE(length(o.force) - previous, 8.5 / 200.0 + 1e-9) << i;
        previous = length(o.force);
    }
    EXPECT_NEAR(previous, 8.5, 1e-9);
}

TEST(ForceRenderer, RejectsBadConfig) {
    ForceRendererConfig c;
    c.rate_hz = 0.0;
    EXPECT_THROW(ForceRenderer{c}, std::invalid_argument);
    c = {};
    c.ramp_ns = 0;
    EXPECT_THROW(ForceRenderer{c}, std::invalid_argument);
    c = {};
    c.min_blend_ticks = 0;
    EXPECT_THROW(ForceRenderer{c}, std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
