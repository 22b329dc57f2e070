// Shallow water by virtual pipes on a TIN (water/virtual_pipes.hpp), against oracles that do
// not come from the scheme: a lake at rest stays at rest over any bed; the volume is exact and
// no depth goes negative; water in a bowl settles to the level whose lake holds its volume
// (found by bisection on the bed alone); a dam-break front travels no faster than Ritter's
// 2 sqrt(g h0); dry terrain costs nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tin/tin.hpp"
#include "util/thread_pool.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_borders.hpp"

namespace sandtin {
namespace {
namespace virtual_pipes_test {

double bumpy_bed(Vec2 p) {
    return 0.05 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y) + 0.03 * p.x;
}

/// Runs `steps` steps at the stable time step; true when no depth ever went negative.
bool run(VirtualPipes& w, int steps) {
    bool non_negative = true;
    for (int k = 0; k < steps; ++k) {
        const double dt = w.stable_time_step();
        if (!std::isfinite(dt)) break;
        w.step(dt);
        for (double d : w.depths())
            non_negative = non_negative && d >= 0.0;
    }
    return non_negative;
}

/// The level L at which a lake over the mesh's bed holds `volume`: sum(area max(0, L - bed))
/// = volume, by bisection.
double lake_level(const WaterMesh& m, double volume) {
    double lo = *std::min_element(m.bed.begin(), m.bed.end());
    double hi = *std::max_element(m.bed.begin(), m.bed.end()) + 10.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        double held = 0.0;
        for (std::size_t v = 0; v < m.bed.size(); ++v)
            held += m.area[v] * std::max(0.0, mid - m.bed[v]);
        (held < volume ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(VirtualPipes, ALakeAtRestOverABumpyBedStaysAtRest) {
    const Tin tin =
        Tin::random_points(Rect::from_size(1.0, 1.0), 1500, 4, bumpy_bed, TinOptions{false});
    VirtualPipes w(water_mesh_of(tin));
    const double level = 0.01;  // islands stand out of it
    std::size_t wet = 0, dry = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double d = std::max(0.0, level - w.mesh().bed[v]);
        w.set_depth(v, d);
        (d > 0.0 ? wet : dry) += 1;
    }
    ASSERT_GT(wet, 100u);
    ASSERT_GT(dry, 100u);
    ASSERT_TRUE(run(w, 2000));
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.mesh().bed[v] < level) {
            EXPECT_NEAR(w.surface(v), level, 1e-12) << v;
        } else {
            EXPECT_EQ(w.depth(v), 0.0) << "dry land got wet at " << v;
        }
    }
}

TEST(VirtualPipes, TheVolumeIsExactAndNoDepthGoesNegative) {
    const Tin tin =
        Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 9, bumpy_bed, TinOptions{false});
    VirtualPipeOptions undamped;
    undamped.friction = 0.0;  // waves slosh for the whole run: the hardest case for both
    VirtualPipes w(water_mesh_of(tin), undamped);
    // A column of water in one corner, on the bumps: fronts run over dry ground.
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const Vec2 p = w.mesh().position[v];
        if (p.x < 0.3 && p.y < 0.4) w.set_depth(v, 0.04 + 0.02 * p.y);
    }
    const double before = w.volume();
    ASSERT_GT(before, 0.0);
    EXPECT_TRUE(run(w, 5000));
    EXPECT_NEAR(w.volume(), before, 1e-12 * before);
    // It spread: water reached the far half of the square.
    double far = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.mesh().position[v].x > 0.6) far += w.depth(v) * w.mesh().area[v];
    }
    EXPECT_GT(far, 0.0);
}

TEST(VirtualPipes, WaterPouredInABowlSettlesToTheLevelThatHoldsItsVolume) {
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 40, 40,
        [](Vec2 p) { return 0.5 * ((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.45) * (p.y - 0.45)); },
        TinOptions{false});
    VirtualPipeOptions options;
    options.friction = 2.0;
    VirtualPipes w(water_mesh_of(tin), options);
    // 2 litres in at one vertex near the bottom.
    std::size_t centre = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (length(w.mesh().position[v] - Vec2{0.5, 0.5}) <
            length(w.mesh().position[centre] - Vec2{0.5, 0.5}))
            centre = v;
    }
    const double volume = 0.002;
    w.add_water(centre, volume);
    // Flat to 2e-10 m after 2 000 steps (20 s of water), 1e-14 after 3 000.
    ASSERT_TRUE(run(w, 3000));
    const double level = lake_level(w.mesh(), volume);
    std::size_t wet = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.depth(v) > 0.0) {
            ++wet;
            EXPECT_NEAR(w.surface(v), level, 1e-5) << v;
        } else {
            EXPECT_GE(w.mesh().bed[v], level - 1e-5) << "dry below the lake at " << v;
        }
    }
    EXPECT_GT(wet, 20u);
    EXPECT_NEAR(w.volume(), volume, 1e-12 * volume);
}

TEST(VirtualPipes, ADamBreakFrontTravelsNoFasterThanRitter) {
    // Flat dry bed, water 5 cm deep on x < 0.3. Ritter's solution: the front on a dry bed
    // moves at 2 sqrt(g h0); the scheme's waves at sqrt(g h) or slower, so no faster.
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 100, 10, [](Vec2) { return 0.0; }, TinOptions{false});
    VirtualPipeOptions options;
    options.friction = 0.0;
    VirtualPipes w(water_mesh_of(tin), options);
    const double h0 = 0.05, dam = 0.3, g = options.gravity;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.mesh().position[v].x < dam) w.set_depth(v, h0);
    }
    double t = 0.0;
    const double until = 0.15;  // s: the front at most 0.21 m past the dam, inside the square
    while (t < until) {
        const double dt = std::min(w.stable_time_step(), until - t);
        w.step(dt);
        t += dt;
    }
    double front = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (w.depth(v) > 1e-6 * h0) front = std::max(front, w.mesh().position[v].x);
    }
    const double spacing = 0.01;  // the grid's along x
    EXPECT_LE(front, dam + 2.0 * std::sqrt(g * h0) * until + 2.0 * spacing);
    // ...and at the order of the wave speed sqrt(g h0): measured 0.39 m, against 0.405 m for
    // a linear wave and 0.51 m for Ritter's front.
    EXPECT_GT(front, dam + 0.5 * std::sqrt(g * h0) * until) << "the water hardly left the dam";
}

TEST(VirtualPipes, FlowVectorsCancelWhereTheFlowIsSymmetricAndPointDownstream) {
    // A mound of water centred on the middle vertex of a regular grid (centrally symmetric,
    // as is the grid's triangulation) on a flat bed: the middle vertex sends as much one way
    // as the opposite way, so its flow vector vanishes while its pipes carry water; away from
    // it the water spreads outwards, and the vector points away from the middle.
    const Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 20, 20);
    VirtualPipes w(water_mesh_of(tin));
    const WaterMesh& m = w.mesh();
    const Vec2 middle{0.5, 0.5};
    std::size_t centre = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double r = length(m.position[v] - middle);
        if (r < length(m.position[centre] - middle)) centre = v;
        if (r < 0.3) w.set_depth(v, 0.02 * (1.0 - r / 0.3));
    }
    // Five steps: the mound is slumping (after about 17 its middle runs dry as the water
    // rings outwards).
    for (int k = 0; k < 5; ++k)
        w.step(w.stable_time_step());
    const std::vector<Vec2> flow = w.flow_vectors();
    double through_centre = 0.0;
    for (const VirtualPipes::Pipe& p : w.pipes())
        if (p.a == centre || p.b == centre) through_centre += std::abs(p.flux);
    ASSERT_LT(length(m.position[centre] - middle), 1e-9);
    ASSERT_GT(through_centre, 1e-6);
    EXPECT_LE(length(flow[centre]), 1e-9 * through_centre);
    std::size_t outward = 0, checked = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const double r = length(m.position[v] - middle);
        if (r < 0.1 || r > 0.25 || length(flow[v]) == 0.0) continue;
        ++checked;
        outward += dot(flow[v], m.position[v] - middle) > 0.0 ? 1 : 0;
    }
    ASSERT_GT(checked, 20u);
    EXPECT_EQ(outward, checked) << "a spreading mound's flow points away from its middle";
}

TEST(VirtualPipes, TwoThreadsStepAsOneDoesToRoundingAndKeepTheVolume) {
    // A mound of water draining over the open east side (at its corner: the random points have
    // no other vertex on it), 300 steps, on one thread and on two:
    // the same depths up to the rounding of a vertex's sums grouped otherwise, the volume plus
    // what left kept to 1e-12 on both, and two runs on two threads the same bits.
    const Tin tin =
        Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 8, bumpy_bed, TinOptions{false});
    const auto mound = [&] {
        VirtualPipes w(water_mesh_of(tin));
        OpenSides east;
        east.east = true;
        const std::vector<double> widths = outflow_widths(w.mesh(), tin.domain(), east);
        for (std::size_t v = 0; v < w.vertex_count(); ++v) {
            const double r = length(w.mesh().position[v] - Vec2{0.85, 0.15});  // over a corner
            if (r < 0.3) w.set_depth(v, 0.04 * (1.0 - r / 0.3));
            w.set_outflow_width(v, widths[v]);
        }
        return w;
    };
    VirtualPipes one = mound(), two = mound(), again = mound();
    const double start = one.volume();
    ThreadPool single(1), pair(2);
    const double dt = one.stable_time_step();
    std::size_t limited = 0;
    for (int k = 0; k < 300; ++k) {
        one.step(dt, single);
        limited += two.step(dt, pair).outflows_limited;
        again.step(dt, pair);
    }
    EXPECT_GT(limited, 0u);  // the front's scaling ran on both threads
    double worst = 0.0, deepest = 0.0;
    for (std::size_t v = 0; v < one.vertex_count(); ++v) {
        worst = std::max(worst, std::abs(one.depth(v) - two.depth(v)));
        deepest = std::max(deepest, one.depth(v));
        ASSERT_GE(two.depth(v), 0.0);
        EXPECT_EQ(two.depth(v), again.depth(v)) << v;
    }
    EXPECT_GT(one.volume_left(), 1e-7);  // water did leave (1.3e-6 m³)
    EXPECT_LE(worst, 1e-12 * deepest);
    EXPECT_NEAR(one.volume() + one.volume_left(), start, 1e-12 * start);
    EXPECT_NEAR(two.volume() + two.volume_left(), start, 1e-12 * start);
    EXPECT_NEAR(two.volume_left(), one.volume_left(), 1e-12 * start);
}

TEST(VirtualPipes, DryTerrainCostsNothingAndBadInputIsRefused) {
    const Tin tin =
        Tin::regular_grid(Rect::from_size(1.0, 1.0), 10, 10, bumpy_bed, TinOptions{false});
    VirtualPipes w(water_mesh_of(tin));
    EXPECT_TRUE(std::isinf(w.stable_time_step()));
    EXPECT_EQ(w.step(0.01).pipes_updated, 0u);
    w.add_water(5, 1e-4);
    EXPECT_EQ(w.step(0.001).pipes_updated, w.pipe_count());
    EXPECT_THROW(w.set_depth(0, -1.0), std::invalid_argument);
    EXPECT_THROW(w.set_depth(w.vertex_count(), 1.0), std::invalid_argument);
    EXPECT_THROW(w.step(0.0), std::invalid_argument);
    EXPECT_THROW(w.step(std::nan("")), std::invalid_argument);
    WaterMesh bad = water_mesh_of(tin);
    bad.bed.pop_back();
    EXPECT_THROW(VirtualPipes{bad}, std::invalid_argument);
    WaterMesh corner = water_mesh_of(tin);
    corner.faces.push_back({0, 1, 100000});
    EXPECT_THROW(VirtualPipes{corner}, std::invalid_argument);
    VirtualPipeOptions no_gravity;
    no_gravity.gravity = 0.0;
    EXPECT_THROW(VirtualPipes(water_mesh_of(tin), no_gravity), std::invalid_argument);
}

}  // namespace virtual_pipes_test
}  // namespace
}  // namespace sandtin
