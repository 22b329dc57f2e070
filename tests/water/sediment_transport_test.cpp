// Sand carried by the water (water/sediment_transport.hpp): the sand on the bed plus the sand
// in the water is exact; the rock is never cut; still water moves nothing; a stream from a
// nozzle down a sandy slope cuts into the slope and drops the sand lower down.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tin/tin.hpp"
#include "water/sediment_transport.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_sources.hpp"

namespace sandtin {
namespace {
namespace sediment_transport_test {

template <class Water>
double sand_on_bed(const Water& w) {
    double sum = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v)
        sum += w.mesh().area[v] * w.mesh().bed[v];
    return sum;
}

/// A plane falling 10 % towards x = 0, with 5 cm of sand over its rock.
Tin sandy_slope() {
    return Tin::regular_grid(
        Rect::from_size(1.0, 0.5), 50, 25, [](Vec2 p) { return 0.1 * p.x + 0.05; },
        TinOptions{false});
}

template <class Water>
std::vector<double> rock_under(const Water& w, double sand) {
    std::vector<double> rock(w.vertex_count());
    for (std::size_t v = 0; v < rock.size(); ++v)
        rock[v] = w.mesh().bed[v] - sand;
    return rock;
}

/// A nozzle's stream down the slope for `seconds`, under either water scheme.
template <class Water>
void stream_down_a_sandy_slope(double seconds) {
    const Tin tin = sandy_slope();
    Water w(water_mesh_of(tin));
    const std::vector<double> bed_before = w.mesh().bed;
    const std::vector<double> rock = rock_under(w, 0.05);
    SedimentTransport sediment(w.mesh(), rock);
    WaterSources nozzle;
    nozzle.nozzles.push_back({{0.9, 0.25}, 0.5});
    const double sand_before = sand_on_bed(w);
    double t = 0.0;
    while (t < seconds) {
        const double dt = std::min(w.stable_time_step(), 0.05);
        apply_sources(w, nozzle, dt);
        w.step(dt);
        sediment.step(w, dt);
        t += dt;
        ASSERT_NEAR(sand_on_bed(w) + sediment.suspended(), sand_before, 1e-12 * sand_before);
    }
    sediment.settle_all(w);
    EXPECT_EQ(sediment.suspended(), 0.0);
    EXPECT_NEAR(sand_on_bed(w), sand_before, 1e-12 * sand_before);
    double deepest_cut = 0.0, highest_fill = 0.0, cut_x = 0.0, fill_x = 0.0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        EXPECT_GE(w.mesh().bed[v], rock[v]) << "the rock was cut at " << v;
        const double change = w.mesh().bed[v] - bed_before[v];
        if (-change > deepest_cut) {
            deepest_cut = -change;
            cut_x = w.mesh().position[v].x;
        }
        if (change > highest_fill) {
            highest_fill = change;
            fill_x = w.mesh().position[v].x;
        }
    }
    EXPECT_GT(deepest_cut, 1e-4) << "the stream cut no channel";
    EXPECT_GT(highest_fill, 1e-5) << "the sand was dropped nowhere";
    EXPECT_LT(fill_x, cut_x) << "the sand went uphill";
}

TEST(SedimentTransport, AStreamDownASandySlopeCutsItAndDropsTheSandLowerHoldingEveryGrain) {
    stream_down_a_sandy_slope<VirtualPipes>(20.0);
}

TEST(SedimentTransport, UnderFiniteVolumesTooAStreamCutsAndDropsHoldingEveryGrain) {
    stream_down_a_sandy_slope<ShallowWater>(1.0);
}

TEST(SedimentTransport, GravelWashedDownstreamIsLaidDownAsGravel) {
    // 5 cm of gravel (material 2) on the slope's upper fifth (x > 0.8, where the nozzle is);
    // below it bare rock labelled sand (0), which the water cannot cut. Every grain dropped
    // below the gravel came from it, so wherever sand was dropped there, it is gravel; where
    // none was, the bed keeps its own label.
    const Tin tin = sandy_slope();
    VirtualPipes w(water_mesh_of(tin));
    std::vector<std::uint16_t> material(w.vertex_count(), 0);
    std::vector<double> rock = w.mesh().bed;
    for (std::size_t v = 0; v < material.size(); ++v) {
        if (w.mesh().position[v].x > 0.8) {
            material[v] = 2;
            rock[v] -= 0.05;
        }
    }
    SedimentTransport sediment(w.mesh(), rock, {}, material);
    WaterSources nozzle;
    nozzle.nozzles.push_back({{0.9, 0.25}, 0.5});
    for (double t = 0.0; t < 3.0;) {
        const double dt = std::min(w.stable_time_step(), 0.05);
        apply_sources(w, nozzle, dt);
        w.step(dt);
        sediment.step(w, dt);
        t += dt;
    }
    sediment.settle_all(w);
    std::size_t gravel_below = 0, untouched = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        if (sediment.dropped(v) == 0.0) {
            ++untouched;
            EXPECT_EQ(sediment.deposited_material(v), material[v]);
        } else if (w.mesh().position[v].x < 0.79) {
            EXPECT_EQ(sediment.deposited_material(v), 2) << "at x = " << w.mesh().position[v].x;
            ++gravel_below;
        }
    }
    EXPECT_GT(gravel_below, 5u) << "no gravel reached the rock below";
    EXPECT_GT(untouched, 0u);
    // Without materials, everything is material 0.
    SedimentTransport plain(w.mesh(), rock_under(w, 0.05));
    EXPECT_EQ(plain.deposited_material(0), 0);
    EXPECT_THROW(SedimentTransport(w.mesh(), rock_under(w, 0.05), {}, {1, 2}),
                 std::invalid_argument);
}

TEST(SedimentTransport, StillWaterMovesNoSand) {
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 20, 20,
        [](Vec2 p) { return 0.05 * std::sin(6.0 * p.x) * std::cos(4.0 * p.y); }, TinOptions{false});
    VirtualPipes w(water_mesh_of(tin));
    for (std::size_t v = 0; v < w.vertex_count(); ++v)
        w.set_depth(v, std::max(0.0, 0.02 - w.mesh().bed[v]));
    const std::vector<double> before = w.mesh().bed;
    SedimentTransport sediment(w.mesh(), rock_under(w, 0.1));
    for (int k = 0; k < 300; ++k) {
        const double dt = w.stable_time_step();
        w.step(dt);
        sediment.step(w, dt);
    }
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        EXPECT_NEAR(w.mesh().bed[v], before[v], 1e-12) << v;
    }
}

TEST(SedimentTransport, BareRockIsNeverCut) {
    const Tin tin = sandy_slope();
    VirtualPipes w(water_mesh_of(tin));
    const std::vector<double> rock = w.mesh().bed;  // no sand at all
    SedimentTransport sediment(w.mesh(), rock);
    WaterSources nozzle;
    nozzle.nozzles.push_back({{0.9, 0.25}, 1.0});
    for (int k = 0; k < 200; ++k) {
        const double dt = std::min(w.stable_time_step(), 0.05);
        apply_sources(w, nozzle, dt);
        w.step(dt);
        sediment.step(w, dt);
    }
    EXPECT_EQ(sediment.suspended(), 0.0);
    EXPECT_EQ(w.mesh().bed, rock);
    // Bedrock above the bed, or not a number, is refused.
    std::vector<double> above = rock;
    above[3] += 0.01;
    EXPECT_THROW(SedimentTransport(w.mesh(), above), std::invalid_argument);
    above[3] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(SedimentTransport(w.mesh(), above), std::invalid_argument);
    SedimentOptions negative;
    negative.drop_rate = -1.0;
    EXPECT_THROW(SedimentTransport(w.mesh(), rock, negative), std::invalid_argument);
}

}  // namespace sediment_transport_test
}  // namespace
}  // namespace sandtin
