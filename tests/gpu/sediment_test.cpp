// GPU sediment (gpu/gpu_sediment.hpp) against its CPU reference in double
// (water/sediment_transport.hpp over water/virtual_pipes.hpp, pipe by pipe rather than vertex
// by vertex), and what the law owes on its own: sand plus suspension kept to float rounding,
// the rock never eroded, materials carried with the sand, everything dropped at the end.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "gpu/gpu_sediment.hpp"
#include "gpu/gpu_water.hpp"
#include "gpu_fixture.hpp"
#include "water/sediment_transport.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

const Rect kBeach = Rect::from_size(1.0, 1.0);

/// A sand slope falling 10 cm to the east with ripples, and 4 cm of water in a mound at its
/// top: it runs down, picks sand up where it is fast and drops it where it slows.
/// `gravel_top`: the top third is gravel (material 1). `rock_depth` > 0: bedrock that far
/// under the top half's sand.
Tin stream_terrain(bool gravel_top = false, double rock_depth = 0.0) {
    Tin tin = Tin::random_points(kBeach, 2500, 17, [](Vec2 p) {
        return 0.1 * (1.0 - p.x) + 0.004 * std::sin(23.0 * p.y) * std::cos(11.0 * p.x);
    });
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const Vec2 p = va.position[v];
        const double r = length(p - Vec2{0.2, 0.5});
        if (r < 0.2) tin.set_water_depth(VertexId{v}, 0.04 * (1.0 - r / 0.2));
        if (gravel_top && p.x < 0.33) tin.set_material(VertexId{v}, 1);
        if (rock_depth > 0.0 && p.x < 0.5) tin.set_bedrock(VertexId{v}, va.height[v] - rock_depth);
    }
    return tin;
}

struct CpuStream {
    VirtualPipes pipes;
    SedimentTransport sediment;
};

CpuStream cpu_stream(const Tin& tin) {
    VirtualPipes pipes(water_mesh_of(tin), VirtualPipeOptions{});
    load_water_depths(pipes, tin);
    const VertexArrays& va = tin.vertices();
    std::vector<double> bedrock(va.bedrock.begin(), va.bedrock.end());
    std::vector<std::uint16_t> material(va.material.begin(), va.material.end());
    SedimentTransport sediment(pipes.mesh(), bedrock, SedimentOptions{}, material);
    return {std::move(pipes), std::move(sediment)};
}

class GpuSedimentTest : public GpuTest {};

TEST_F(GpuSedimentTest, CarvesAsTheCpuLawDoes) {
    Tin tin = stream_terrain();
    const std::vector<double> start = tin.vertices().height;
    CpuStream cpu = cpu_stream(tin);
    const double dt = 0.5 * cpu.pipes.stable_time_step();
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    GpuSediment sediment(water);
    const int steps = 300;
    for (int i = 0; i < steps; ++i) {
        cpu.pipes.step(dt);
        cpu.sediment.step(cpu.pipes, dt);
    }
    for (int i = 0; i < steps; i += 100)
        water.run(100, dt, &sediment);
    const std::vector<double> beds = sediment.read_beds();
    const VertexArrays& va = tin.vertices();
    double change = 0.0, worst = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        change = std::max(change, std::abs(cpu.pipes.mesh().bed[v] - start[v]));
        worst = std::max(worst, std::abs(beds[v] - cpu.pipes.mesh().bed[v]));
    }
    std::printf("bed change %.3g m, GPU - CPU %.3g m; suspended CPU %.6g GPU %.6g m3\n", change,
                worst, cpu.sediment.suspended(), sediment.suspended());
    ASSERT_GT(change, 1e-4);          // the stream did carve: the comparison means something
    EXPECT_LE(worst, 2e-3 * change);  // measured 2.6e-4 of it
    EXPECT_NEAR(sediment.suspended(), cpu.sediment.suspended(), 1e-3 * cpu.sediment.suspended());
}

TEST_F(GpuSedimentTest, KeepsTheSandAndDropsItAllAtTheEnd) {
    Tin tin = stream_terrain();
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    GpuSediment sediment(water);
    const double before = sediment.sand_volume();
    const double dt = water.stable_time_step();
    for (int i = 0; i < 5; ++i)
        water.run(200, dt, &sediment);
    EXPECT_GT(sediment.suspended(), 0.0);
    const double during = sediment.sand_volume();
    sediment.settle_all();
    EXPECT_EQ(sediment.suspended(), 0.0);
    const double after = sediment.sand_volume();
    std::printf("sand %.12g -> %.12g -> %.12g m3\n", before, during, after);
    // 6e-4 m3 of sand in float heights, each change's rounding kept in the bed residual:
    // measured 5e-13 m3 of drift (8e-10 of the sand).
    EXPECT_NEAR(during, before, 1e-11);
    EXPECT_NEAR(after, before, 1e-11);
    // Handed back to the terrain: the same volume the terrain now holds.
    EXPECT_GT(sediment.copy_beds_into(tin), 0u);
}

TEST_F(GpuSedimentTest, NeverErodesTheRock) {
    Tin tin = stream_terrain(false, 2e-4);  // 0.2 mm of sand over rock on the top half
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    GpuSediment sediment(water);
    const double dt = water.stable_time_step();
    for (int i = 0; i < 5; ++i)
        water.run(200, dt, &sediment);
    const std::vector<double> beds = sediment.read_beds();
    const VertexArrays& va = tin.vertices();
    int on_rock = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || va.bedrock[v] <= kNoBedrock) continue;
        // The mirror's bedrock rounds up to a float: never below the terrain's.
        EXPECT_GE(beds[v], va.bedrock[v] - 1e-9) << v;
        on_rock += beds[v] < va.bedrock[v] + 1e-6 ? 1 : 0;
    }
    EXPECT_GT(on_rock, 0);  // the water did take the sand down to the rock somewhere
}

TEST_F(GpuSedimentTest, GravelWashedDownStaysGravelAsOnTheCpu) {
    Tin tin = stream_terrain(true);
    CpuStream cpu = cpu_stream(tin);
    const double dt = 0.5 * cpu.pipes.stable_time_step();
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    GpuSediment sediment(water);
    for (int i = 0; i < 600; ++i) {
        cpu.pipes.step(dt);
        cpu.sediment.step(cpu.pipes, dt);
    }
    cpu.sediment.settle_all(cpu.pipes);
    for (int i = 0; i < 6; ++i)
        water.run(100, dt, &sediment);
    sediment.settle_all();
    const std::vector<std::uint16_t> kinds = sediment.deposited_materials();
    const std::vector<double> dropped = sediment.dropped();
    const VertexArrays& va = tin.vertices();
    int gravel_on_sand = 0, compared = 0, agreeing = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || cpu.sediment.dropped(v) < 1e-9) continue;
        ++compared;
        agreeing += kinds[v] == cpu.sediment.deposited_material(v) ? 1 : 0;
        gravel_on_sand += va.material[v] == 0 && kinds[v] == 1 ? 1 : 0;
        EXPECT_NEAR(dropped[v], cpu.sediment.dropped(v), 0.05 * cpu.sediment.dropped(v) + 1e-9);
    }
    ASSERT_GT(compared, 50);
    EXPECT_GT(gravel_on_sand, 0);  // gravel carried beyond the gravel
    EXPECT_GE(agreeing, compared * 98 / 100);
}

TEST_F(GpuSedimentTest, BedsHandedBackBeforeTheWaterKeepTheSandAcrossRuns) {
    // The editor's round: run, hand the beds then the water back to the terrain (journaled:
    // the mirror uploads those vertices again), run again. The terrain's own sand plus what
    // the GPU still carries is the sand the terrain started with.
    Tin tin = stream_terrain();
    const double start = tin.volume();
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    GpuSediment sediment(water);
    const double dt = water.stable_time_step();
    for (int round = 0; round < 4; ++round) {
        water.run(100, dt, &sediment);
        EXPECT_GT(sediment.copy_beds_into(tin), 0u) << round;
        water.copy_depths_into(tin);
    }
    sediment.settle_all();
    sediment.copy_beds_into(tin);
    EXPECT_EQ(sediment.suspended(), 0.0);
    EXPECT_EQ(sediment.suspended_lost(), 0.0);
    // Beds handed back with their residuals; each round's upload rounds the terrain's doubles
    // to the mirror's floats again (measured 7.7e-11 m3 on 0.05 m3; without the residuals
    // 4.6e-9).
    std::printf("terrain %.15g -> %.15g m3\n", start, tin.volume());
    EXPECT_NEAR(tin.volume(), start, 1e-9);
}

TEST_F(GpuSedimentTest, RefusesBadConstants) {
    Tin tin = stream_terrain();
    TinMirror mirror(ctx(), tin);
    GpuWater water(mirror);
    SedimentOptions bad;
    bad.pick_up_rate = -1.0;
    EXPECT_THROW(GpuSediment(water, bad), GpuError);
    bad = SedimentOptions{};
    bad.max_concentration = 1.5;
    EXPECT_THROW(GpuSediment(water, bad), GpuError);
    for (std::uint32_t v = 0; v < 9; ++v)
        tin.set_material(VertexId{v}, static_cast<std::uint16_t>(v));
    EXPECT_THROW(GpuSediment(water, {}), GpuError);  // nine materials: more than it carries
}

}  // namespace
}  // namespace sandtin::gpu
