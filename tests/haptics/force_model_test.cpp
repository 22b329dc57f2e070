// The force model against values computed by hand from the seeds' formulas
// (force_model.hpp): F_p = k (h - z + δ), F_r = -(μ k / N) Σ u_i m_i, gel 0.2 N, clamp F_M.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "haptics/force_model.hpp"

namespace sandtin::haptics {
namespace {

constexpr double kK = 800.0;  // N/m
constexpr double kMu = 0.55;
constexpr double kDelta = 0.000625;

// A ring of n control points of radius r around (0.5, 0.5), all on terrain height h.
HapticSnapshot flat_ring(double h, int n = 12, double r = 0.04) {
    HapticSnapshot s;
    s.sequence = 1;
    s.centre = {0.5, 0.5};
    s.centre_height = h;
    s.control_count = static_cast<std::uint32_t>(n);
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        s.control[static_cast<std::size_t>(i)] = {0.5 + r * std::cos(a), 0.5 + r * std::sin(a)};
        s.control_height[static_cast<std::size_t>(i)] = h;
    }
    s.stiffness = kK;
    s.friction = kMu;
    return s;
}

ForceModelParams params() {
    ForceModelParams p;
    p.contact_offset = kDelta;
    return p;
}

TEST(ForceModel, ZeroAboveTheSurface) {
    const HapticSnapshot s = flat_ring(0.1);
    for (double above : {kDelta * 1.0001, 0.001, 0.01, 1.0}) {
        const ForceSample f =
            evaluate_force(s, {0.5, 0.5, 0.1 + above}, {0.3, -0.2, 0.0}, params());
        EXPECT_FALSE(f.contact) << above;
        EXPECT_EQ(f.force, (Vec3{})) << above;
    }
    // Off-centre and moving: still nothing.
    EXPECT_EQ(evaluate_force(s, {0.52, 0.49, 0.2}, {1, 1, 1}, params()).force, (Vec3{}));
}

TEST(ForceModel, NoSnapshotNoForce) {
    HapticSnapshot s = flat_ring(0.1);
    s.sequence = 0;
    EXPECT_EQ(evaluate_force(s, {0.5, 0.5, 0.0}, {}, params()).force, (Vec3{}));
}

TEST(ForceModel, PenetrationMatchesHandValues) {
    const HapticSnapshot s = flat_ring(0.1);
    // depth 2 mm: k (0.002 + 0.000625) = 800 * 0.002625 = 2.1 N, straight up.
    const ForceSample f = evaluate_force(s, {0.5, 0.5, 0.098}, {}, params());
    EXPECT_TRUE(f.contact);
    EXPECT_NEAR(f.force.z, 2.1, 1e-9);
    EXPECT_NEAR(f.force.x, 0.0, 1e-12);
    EXPECT_NEAR(f.force.y, 0.0, 1e-12);
    EXPECT_NEAR(f.immersion, 0.002, 1e-12);
    // At exact contact: k δ = 0.5 N (seed 004: 0.05 units x 10 N).
    EXPECT_NEAR(evaluate_force(s, {0.5, 0.5, 0.1}, {}, params()).force.z, 0.5, 1e-9);
}

TEST(ForceModel, GrowsWithDepth) {
    const HapticSnapshot s = flat_ring(0.0);
    double previous = -1.0;
    for (int i = 0; i <= 20; ++i) {
        const double depth = -kDelta + 0.0005 * i + 1e-7;
        const double fz = evaluate_force(s, {0.5, 0.5, -depth}, {}, params()).force.z;
        EXPECT_GE(fz, previous) << depth;
        if (fz > 0.2 + 1e-9 && fz < 10.0 - 1e-9) {
            EXPECT_NEAR(fz, kK * (depth + kDelta), 1e-9);
            EXPECT_GT(fz, previous) << depth;
        }
        previous = fz;
    }
}

TEST(ForceModel, GelMinimumOnContact) {
    const HapticSnapshot s = flat_ring(0.0);
    // Just inside the onset band: k (δ - 0.6 mm) = 800 * 0.000025 = 0.02 N -> raised to 0.2 N.
    const ForceSample f = evaluate_force(s, {0.5, 0.5, 0.0006}, {}, params());
    EXPECT_TRUE(f.contact);
    EXPECT_NEAR(length(f.force), 0.2, 1e-12);
    EXPECT_NEAR(f.force.z, 0.2, 1e-12);
}

TEST(ForceModel, NeverExceedsTheClamp) {
    const HapticSnapshot s = flat_ring(0.5);
    for (double depth : {0.0125, 0.02, 0.1, 1.0, 100.0}) {
        for (Vec3 v : {Vec3{}, Vec3{50, -50, 0}, Vec3{1e6, 0, 0}}) {
            const ForceSample f = evaluate_force(s, {0.51, 0.5, 0.5 - depth}, v, params());
            EXPECT_LE(length(f.force), 10.0 + 1e-12) << depth;
        }
    }
    // 1.2 cm deep on flat sand: k (0.012 + δ) = 10.1 N -> clamped to exactly 10 N.
    EXPECT_NEAR(evaluate_force(s, {0.5, 0.5, 0.488}, {}, params()).force.z, 10.0, 1e-9);
    ForceModelParams small = params();
    small.max_force = 3.3;
    EXPECT_NEAR(length(evaluate_force(s, {0.5, 0.5, 0.49}, {}, small).force), 3.3, 1e-12);
}

TEST(ForceModel, DirectionalTermSymmetricAtRestOnFlatSand) {
    for (int n : {3, 4, 12, 13, 64}) {
        const HapticSnapshot s = flat_ring(0.2, n);
        const ForceSample f = evaluate_force(s, {0.5, 0.5, 0.197}, {}, params());
        EXPECT_NEAR(f.force.x, 0.0, 1e-12) << n;
        EXPECT_NEAR(f.force.y, 0.0, 1e-12) << n;
        EXPECT_NEAR(f.force.z, kK * (0.003 + kDelta), 1e-9) << n;
        // The pen wandering inside the ring between snapshots changes nothing sideways.
        const ForceSample g = evaluate_force(s, {0.51, 0.495, 0.197}, {}, params());
        EXPECT_NEAR(g.force.x, 0.0, 1e-12) << n;
        EXPECT_NEAR(g.force.y, 0.0, 1e-12) << n;
    }
}

TEST(ForceModel, DirectionalTermPushesAwayFromMaterial) {
    // Four control points on the axes; only the +x one is on a 4 mm higher step.
    HapticSnapshot s = flat_ring(0.0, 4);
    s.control_height[0] = 0.004;  // the point at +x
    // Tool bottom 1 mm below the flat part: m = 0.001 + δ on three points, 0.005 + δ on +x.
    // Σ u_i m_i = (+x)(0.005625) + (-x)(0.001625) + (±y)(0.001625) = (0.004, 0) m;
    // F_r = -(μ k / 4) (0.004, 0) = -(0.55 * 800 / 4) * 0.004 = -0.44 N along x.
    const ForceSample f = evaluate_force(s, {0.5, 0.5, -0.001}, {}, params());
    EXPECT_NEAR(f.force.x, -0.44, 1e-9);
    EXPECT_NEAR(f.force.y, 0.0, 1e-12);
    EXPECT_NEAR(f.force.z, kK * (0.001 + kDelta), 1e-9);
    // Only the wall touches (tool above the flat part): still in contact, pushed away from it.
    const ForceSample w = evaluate_force(s, {0.5, 0.5, 0.002}, {}, params());
    EXPECT_TRUE(w.contact);
    // m = 0.002 + δ on +x: F_x = -(440 / 4) * 0.002625 = -0.28875 N; F_z = 0.
    EXPECT_NEAR(w.force.x, -0.28875, 1e-9);
    EXPECT_NEAR(w.force.z, 0.0, 1e-12);
}

TEST(ForceModel, StiffnessAndFrictionComeFromTheSnapshotMaterial) {
    HapticSnapshot s = flat_ring(0.0, 4);
    s.control_height[0] = 0.004;
    s.stiffness = 1600.0;
    s.friction = 0.8;
    const ForceSample f = evaluate_force(s, {0.5, 0.5, -0.001}, {}, params());
    EXPECT_NEAR(f.force.z, 1600.0 * (0.001 + kDelta), 1e-9);
    EXPECT_NEAR(f.force.x, -(0.8 * 1600.0 / 4.0) * 0.004, 1e-9);
}

TEST(ForceModel, GelDragOpposesHorizontalMotion) {
    const HapticSnapshot s = flat_ring(0.0);
    // 0.01 N s/m at 0.5 m/s = 0.005 N against the motion.
    const ForceSample f = evaluate_force(s, {0.5, 0.5, -0.002}, {0.5, 0.0, 0.0}, params());
    EXPECT_NEAR(f.force.x, -0.005, 1e-12);
}

TEST(ForceModel, MaterialInADirectionInterpolatesAlongTheCrossedEdge) {
    // A square ring of half-width 4 cm around the centre, corner heights 0, 1, 2, 3 mm.
    HapticSnapshot s;
    s.sequence = 1;
    s.centre = {0.5, 0.5};
    s.control_count = 4;
    s.control[0] = {0.54, 0.46};
    s.control[1] = {0.54, 0.54};
    s.control[2] = {0.46, 0.54};
    s.control[3] = {0.46, 0.46};
    s.control_height = {0.0, 0.001, 0.002, 0.003};
    // +x crosses edge 0-1 halfway: 0.5 mm; +y crosses edge 1-2 halfway: 1.5 mm; towards a
    // corner: that corner's height.
    EXPECT_NEAR(*ring_height_along(s, {1.0, 0.0}), 0.0005, 1e-15);
    EXPECT_NEAR(*ring_height_along(s, {0.0, 2.0}), 0.0015, 1e-15);
    EXPECT_NEAR(*ring_height_along(s, {-1.0, -1.0}), 0.003, 1e-15);
    // A quarter of the way along edge 3-0 (from (0.46, 0.46) to (0.54, 0.46)): direction
    // (-0.02, -0.04); height 3 + (0 - 3) / 4 = 2.25 mm.
    EXPECT_NEAR(*ring_height_along(s, {-0.02, -0.04}), 0.00225, 1e-15);
    EXPECT_FALSE(ring_height_along(s, {0.0, 0.0}).has_value());
}

TEST(ForceModel, ConcaveRingHidesAControlPointBehindANearerEdge) {
    // c4 dents the ring so the ray from the centre towards c0 first crosses edge c3-c4, at
    // u = 0.04 / 0.045 (where that edge meets y = 0): H_0 = 1 + (4 - 1) u mm.
    HapticSnapshot s;
    s.sequence = 1;
    s.centre = {0.0, 0.0};
    s.control_count = 5;
    s.control[0] = {0.04, 0.0};
    s.control[1] = {0.0, 0.04};
    s.control[2] = {-0.04, 0.0};
    s.control[3] = {0.0, -0.04};
    s.control[4] = {0.02, 0.005};
    s.control_height = {0.010, 0.0, 0.0, 0.001, 0.004};
    const double u = 0.04 / 0.045;
    const double h0 = 0.001 + 0.003 * u;
    EXPECT_NEAR(*ring_height_along(s, {1.0, 0.0}), h0, 1e-15);
    const PreparedSnapshot p = prepare_snapshot(s);
    EXPECT_NEAR(p.height_along[0], h0, 1e-15);
    EXPECT_NEAR(p.height_along[1], 0.0, 1e-15);
    EXPECT_NEAR(p.direction[0].x, 1.0, 1e-15);
}

TEST(ForceModel, NonFiniteInputGivesZero) {
    const HapticSnapshot s = flat_ring(0.0);
    EXPECT_EQ(evaluate_force(s, {NAN, 0.5, -0.1}, {}, params()).force, (Vec3{}));
    EXPECT_EQ(evaluate_force(s, {0.5, 0.5, -0.1}, {INFINITY, 0, 0}, params()).force, (Vec3{}));
}

TEST(ForceModel, ClampOfAHugeVectorIsExactlyTheLimitAlongIt) {
    // |v|² overflows beyond ~1e154. 3:0:-4 times 2^1000: scaled by its largest component the
    // vector is (0.75, 0, -1), of length 1.25 exactly, so the clamp is exactly (6, 0, -8).
    const double big = std::ldexp(1.0, 1000);
    EXPECT_EQ(clamp_magnitude({3.0 * big, 0.0, -4.0 * big}, 10.0), (Vec3{6.0, 0.0, -8.0}));
    // The audit's pose: (1e300, 1e300, -1e300) gives |F| = 10 along (1, 1, -1).
    const Vec3 f = clamp_magnitude({1e300, 1e300, -1e300}, 10.0);
    EXPECT_NEAR(length(f), 10.0, 1e-12);
    EXPECT_NEAR(f.x, 10.0 / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(f.y, 10.0 / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(f.z, -10.0 / std::sqrt(3.0), 1e-12);
    // Just past the overflow, and the largest double.
    const double m = std::numeric_limits<double>::max();
    EXPECT_EQ(clamp_magnitude({0.0, m, 0.0}, 10.0), (Vec3{0.0, 10.0, 0.0}));
    EXPECT_EQ(clamp_magnitude({0.0, 0.0, -2e154}, 10.0), (Vec3{0.0, 0.0, -10.0}));
    // Infinite components: the limit along them.
    const double inf = std::numeric_limits<double>::infinity();
    const Vec3 g = clamp_magnitude({inf, 1.0, -inf}, 10.0);
    EXPECT_NEAR(g.x, 10.0 / std::sqrt(2.0), 1e-12);
    EXPECT_EQ(g.y, 0.0);
    EXPECT_NEAR(g.z, -10.0 / std::sqrt(2.0), 1e-12);
    // Ordinary vectors are unchanged by the scaled path: within the limit, or scaled to it.
    EXPECT_EQ(clamp_magnitude({3.0, 0.0, -4.0}, 10.0), (Vec3{3.0, 0.0, -4.0}));
    EXPECT_EQ(clamp_magnitude({30.0, 0.0, -40.0}, 10.0), (Vec3{6.0, 0.0, -8.0}));
}

TEST(ForceModel, AHugeImmersionStillGivesTheClampedForceStraightUp) {
    // k (immersion + δ) overflows for an immersion near the largest double.
    HapticSnapshot s = flat_ring(0.0);
    s.control_count = 0;
    const ForceSample f =
        evaluate_force(s, {0.5, 0.5, -std::numeric_limits<double>::max()}, {}, params());
    EXPECT_TRUE(f.contact);
    EXPECT_EQ(f.force, (Vec3{0.0, 0.0, 10.0}));
}

TEST(ForceModel, NothingToTouchOffTheTerrain) {
    // The terrain is [0, 1] x [0, 1]; a ring of radius 4 cm whose centre is 1 mm past the
    // border x = 0, 3 mm below the surface height h = 0.
    const double depth = 0.003;
    HapticSnapshot s = flat_ring(0.0);
    s.terrain = Rect::from_size(1.0, 1.0);
    const Vec2 centre{-0.001, 0.5};
    s.centre = centre;
    for (int i = 0; i < 12; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 12;
        s.control[static_cast<std::size_t>(i)] = {centre.x + 0.04 * std::cos(a),
                                                  centre.y + 0.04 * std::sin(a)};
    }
    // Oracle: no penetration (the centre is off the terrain); the resistance of the inside
    // points only, at the angles 0, ±30° and ±60° (cos > 1/40), each pushing back along -u_i
    // with m = depth + δ, averaged over all 12 points.
    const double cos_sum = 1.0 + 2.0 * std::cos(std::numbers::pi / 6) + 2.0 * 0.5;
    const double expected_x = -(kMu * kK / 12.0) * cos_sum * (depth + kDelta);
    const ForceSample f = evaluate_force(s, {centre.x, centre.y, -depth}, {}, params());
    EXPECT_TRUE(f.contact);
    EXPECT_NEAR(f.force.x, expected_x, 1e-12);
    EXPECT_NEAR(f.force.y, 0.0, 1e-12);
    EXPECT_EQ(f.force.z, 0.0);
    EXPECT_EQ(f.immersion, -std::numeric_limits<double>::infinity());
    // No greater than fully inside: k (depth + δ) straight up.
    HapticSnapshot inside = flat_ring(0.0);
    inside.terrain = s.terrain;
    const ForceSample g = evaluate_force(inside, {0.5, 0.5, -depth}, {}, params());
    EXPECT_NEAR(g.force.z, kK * (depth + kDelta), 1e-12);
    EXPECT_LE(length(f.force), length(g.force));

    // The whole ring off the terrain: no force, no contact, however deep.
    for (double x : {-0.05, -5.0, 49.0, 1e6}) {
        HapticSnapshot out = flat_ring(0.0);
        out.terrain = s.terrain;
        out.centre = {x, 0.5};
        for (std::uint32_t i = 0; i < out.control_count; ++i)
            out.control[i] = out.control[i] + Vec2{x - 0.5, 0.0};
        for (double z : {-0.001, -0.2, -1e6}) {
            const ForceSample h = evaluate_force(out, {x, 0.5, z}, {0.1, 0.0, 0.0}, params());
            EXPECT_FALSE(h.contact) << x << " " << z;
            EXPECT_EQ(h.force, (Vec3{})) << x << " " << z;
        }
    }
}

}  // namespace
}  // namespace sandtin::haptics
