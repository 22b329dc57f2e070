// GPU virtual pipes (gpu/gpu_water.hpp) against their CPU reference in double
// (water/virtual_pipes.hpp, a second implementation: pipe by pipe, not vertex by vertex), and
// the properties the scheme owes on its own: volume to rounding, a lake at rest, a dry terrain
// that costs no dispatch, an open side, and water kept across a re-triangulation.

#include <algorithm>
#include <cmath>
#include <vector>

#include "gpu/gpu_water.hpp"
#include "gpu_fixture.hpp"
#include "support/tin_oracles.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_borders.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

const Rect kPond = Rect::from_size(1.0, 1.0);

// A bumpy bed falling gently to the east.
double bumpy_bed(Vec2 p) {
    return 0.04 * (1.0 - p.x) + 0.01 * std::sin(9.0 * p.x) * std::cos(7.0 * p.y);
}

Tin bumpy_terrain(std::size_t points = 2500) {
    return Tin::random_points(kPond, points, 11, bumpy_bed);
}

// A mound of water 4 cm high on the west half: it runs east and sloshes.
void pour_mound(Tin& tin) {
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = std::hypot(va.position[v].x - 0.3, va.position[v].y - 0.5);
        const double d = std::max(0.0, 0.04 * (1.0 - r / 0.25));
        if (d > 0.0) tin.set_water_depth(VertexId{v}, d);
    }
}

VirtualPipes cpu_pipes(const Tin& tin) {
    VirtualPipes pipes(water_mesh_of(tin), VirtualPipeOptions{});
    load_water_depths(pipes, tin);
    return pipes;
}

double deepest(const Tin& tin) {
    double d = 0.0;
    for (const double x : tin.vertices().water_depth)
        d = std::max(d, x);
    return d;
}

// Largest |gpu - cpu| depth over the live vertices.
double worst_difference(const Tin& tin, const std::vector<float>& gpu, const VirtualPipes& cpu) {
    const VertexArrays& va = tin.vertices();
    double worst = 0.0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v])
            worst = std::max(worst, std::abs(static_cast<double>(gpu[v]) - cpu.depth(v)));
    }
    return worst;
}

class GpuWaterTest : public GpuTest {};

TEST_F(GpuWaterTest, StableStepIsTheCpuPipesStep) {
    Tin tin = bumpy_terrain();
    pour_mound(tin);
    const VirtualPipes cpu = cpu_pipes(tin);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const double cpu_step = cpu.stable_time_step(), gpu_step = gpu.stable_time_step();
    ASSERT_TRUE(std::isfinite(cpu_step));
    EXPECT_NEAR(gpu_step, cpu_step, 1e-5 * cpu_step);
    EXPECT_NEAR(gpu.deepest(), deepest(tin), 1e-7);
    EXPECT_TRUE(gpu.active());
}

TEST_F(GpuWaterTest, FollowsTheCpuPipesStepForStep) {
    Tin tin = bumpy_terrain();
    pour_mound(tin);
    VirtualPipes cpu = cpu_pipes(tin);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const double dt = cpu.stable_time_step();
    const double scale = deepest(tin);
    // Three submissions of 100 steps: the fluxes carry over between runs.
    for (int run = 0; run < 3; ++run) {
        const GpuWaterRun r = gpu.run(100, dt);
        EXPECT_EQ(r.steps, 100);
        for (int i = 0; i < 100; ++i)
            cpu.step(dt);
        const double worst = worst_difference(tin, gpu.read_depths(), cpu);
        // Float against double over a flow that moved the water across the pond: agreement
        // to 1e-4 of the depth (a wrong conductance, upwind end or scale is off by percents).
        EXPECT_LE(worst, 1e-4 * scale) << "after " << (run + 1) * 100 << " steps";
    }
    EXPECT_GT(cpu.volume(), 0.0);
}

TEST_F(GpuWaterTest, KeepsItsVolumeToRoundingAndNoDepthBelowZero) {
    Tin tin = bumpy_terrain();
    pour_mound(tin);
    const double before = test::water_volume(tin);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const double dt = gpu.stable_time_step();
    // The float areas differ from the double ones by rounding: measure on the GPU's own.
    const double start = gpu.volume();
    EXPECT_NEAR(start, before, 1e-6 * before);
    std::size_t limited = 0;
    for (int run = 0; run < 10; ++run)
        limited += gpu.run(200, dt).outflows_limited;
    EXPECT_GT(limited, 0u) << "the drying front must have scaled some outflows";
    EXPECT_NEAR(gpu.volume(), start, 1e-7 * start);
    for (const float d : gpu.read_depths())
        ASSERT_GE(d, 0.0f);
}

TEST_F(GpuWaterTest, DeepWaterKeepsTheVolumeItsFloatDepthsCannotHold) {
    // Two metres of water with a 5 mm swell: a step moves far less than a float ulp of the
    // depth (2.4e-7 m) at most vertices. Rounding each update would lose or make up to half an
    // ulp a vertex a step, 6e-8 of the volume; the compensated update keeps what the depth
    // cannot take in its residual, so after 1000 steps the volume is that of the start to the
    // rounding of the residuals alone.
    Tin tin = bumpy_terrain();
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = std::hypot(va.position[v].x - 0.5, va.position[v].y - 0.5);
        tin.set_water_depth(VertexId{v}, 2.0 - va.height[v] + 0.005 * std::exp(-r * r / 0.02));
    }
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const double start = gpu.volume();
    const double dt = gpu.stable_time_step();
    for (int run = 0; run < 5; ++run)
        gpu.run(200, dt);
    EXPECT_NEAR(gpu.volume(), start, 1e-9 * start);
}

TEST_F(GpuWaterTest, LakeAtRestStaysAtRest) {
    Tin tin = bumpy_terrain();
    // A level lake at 2.5 cm over the bumps (islands stand out of it).
    const double level = 0.025;
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v] && va.height[v] < level)
            tin.set_water_depth(VertexId{v}, level - va.height[v]);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const std::vector<float> start = gpu.read_depths();
    const double dt = gpu.stable_time_step();
    gpu.run(2000, dt);
    const std::vector<float> end = gpu.read_depths();
    double worst = 0.0;
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) worst = std::max(worst, std::abs(double(end[v]) - double(start[v])));
    // The float surface (height + depth) is level only to its rounding, a few ulps of 4 cm
    // (3.7e-9 m each): the water may even those out, and must do nothing more. An unbalanced
    // scheme moves millimetres here.
    EXPECT_LE(worst, 64 * 3.7e-9);
}

TEST_F(GpuWaterTest, DryTerrainRecordsNothing) {
    Tin tin = bumpy_terrain(400);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    EXPECT_EQ(gpu.run(50, 0.01).steps, 0);
    EXPECT_FALSE(gpu.active());
    // Sand edited elsewhere (heights, even a new vertex) brings no water.
    tin.set_height(VertexId{7}, tin.vertices().height[7] + 0.01);
    tin.insert_point_on_surface({0.52, 0.47});
    EXPECT_EQ(gpu.run(50, 0.01).steps, 0);
    EXPECT_EQ(gpu.dispatches_recorded(), 0u);
    // Water from the CPU wakes it.
    tin.set_water_depth(VertexId{7}, 0.01);
    EXPECT_EQ(gpu.run(5, 0.001).steps, 5);
    EXPECT_TRUE(gpu.active());
    EXPECT_GT(gpu.dispatches_recorded(), 0u);
}

TEST_F(GpuWaterTest, ClearedWaterGoesQuiet) {
    Tin tin = bumpy_terrain(400);
    tin.set_water_depth(VertexId{7}, 0.01);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    EXPECT_TRUE(gpu.run(1, 1e-3).steps == 1);
    // The terrain takes the GPU's water back, then clears it (the editor's Clear water): the
    // next run finds none and stops there.
    gpu.copy_depths_into(tin);
    const VertexArrays& va = tin.vertices();
    std::size_t cleared = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v] && va.water_depth[v] > 0.0) {
            tin.set_water_depth(VertexId{v}, 0.0);
            ++cleared;
        }
    }
    EXPECT_GT(cleared, 1u) << "the water must have spread before it was cleared";
    gpu.run(1, 1e-3);  // steps once on the zeros uploaded, then measures
    EXPECT_FALSE(gpu.active());
    const uint64_t dispatches = gpu.dispatches_recorded();
    EXPECT_EQ(gpu.run(10, 1e-3).steps, 0);
    EXPECT_EQ(gpu.dispatches_recorded(), dispatches);
    EXPECT_TRUE(std::isinf(gpu.stable_time_step()));
}

TEST_F(GpuWaterTest, OpenSideDrainsAsTheCpuPipesDo) {
    Tin tin = bumpy_terrain();
    pour_mound(tin);
    OpenSides east;
    east.east = true;
    VirtualPipes cpu = cpu_pipes(tin);
    const std::vector<double> widths = outflow_widths(cpu.mesh(), kPond, east);
    open_borders(cpu, kPond, east);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    gpu.set_outflow_widths(widths);
    const double start = gpu.volume();
    const double dt = cpu.stable_time_step();
    gpu.run(1500, dt);
    for (int i = 0; i < 1500; ++i)
        cpu.step(dt);
    ASSERT_GT(cpu.volume_left(), 0.05 * cpu.volume()) << "the scene must drain";
    EXPECT_NEAR(gpu.volume_left(), cpu.volume_left(), 1e-3 * cpu.volume_left());
    // What left plus what stays is what there was (the float border sum adds its rounding).
    EXPECT_NEAR(gpu.volume() + gpu.volume_left(), start, 1e-6 * start);
}

TEST_F(GpuWaterTest, KeepsTheWaterAcrossARetriangulation) {
    Tin tin = bumpy_terrain();
    pour_mound(tin);
    TinMirror mirror(ctx(), tin);
    GpuWater gpu(mirror);
    const double dt = gpu.stable_time_step();
    gpu.run(100, dt);
    EXPECT_GT(gpu.copy_depths_into(tin), 0u);
    EXPECT_EQ(gpu.copy_depths_into(tin), 0u) << "a second copy finds nothing changed";
    // A stamp's worth of new vertices under the water: the terrain interpolates their depth.
    for (int i = 0; i < 20; ++i)
        tin.insert_point_on_surface({0.35 + 0.01 * i, 0.5 + 0.003 * i});
    const double after_edit = test::water_volume(tin);
    const GpuWaterRun r = gpu.run(300, 0.5 * dt);
    EXPECT_EQ(r.steps, 300);
    EXPECT_NEAR(gpu.volume(), after_edit, 1e-6 * after_edit);
    for (const float d : gpu.read_depths())
        ASSERT_TRUE(std::isfinite(d) && d >= 0.0f);
    // The GPU's water goes back into the terrain.
    gpu.copy_depths_into(tin);
    EXPECT_NEAR(test::water_volume(tin), gpu.volume(), 1e-6 * after_edit);
}

TEST_F(GpuWaterTest, RefusesBadSettingsAndSteps) {
    Tin tin = bumpy_terrain(100);
    TinMirror mirror(ctx(), tin);
    EXPECT_THROW(GpuWater(mirror, GpuWaterSettings{-1.0, 0.5, 0.5}), GpuError);
    EXPECT_THROW(GpuWater(mirror, GpuWaterSettings{9.81, 0.5, 1.5}), GpuError);
    GpuWater gpu(mirror);
    EXPECT_THROW(gpu.run(1, 0.0), GpuError);
    EXPECT_THROW(gpu.run(1, std::nan("")), GpuError);
    EXPECT_THROW(gpu.run(-1, 0.01), GpuError);
    const std::vector<double> bad{0.0, -1.0};
    EXPECT_THROW(gpu.set_outflow_widths(bad), GpuError);
}

}  // namespace
}  // namespace sandtin::gpu
