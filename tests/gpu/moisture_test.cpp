// GPU moisture (gpu/gpu_moisture.hpp) against its CPU reference in double
// (water/moisture_diffusion.hpp, a second implementation: edge by edge over the vertices the
// moisture reaches, not vertex-parallel over the whole terrain), and the properties the scheme
// owes on its own: sum(A m) kept to float rounding without drying, moisture within [0, 1],
// the exact decay with drying, water wetting the sand under it, a dry terrain that costs no
// dispatch, and a re-triangulation under the moisture.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "gpu/gpu_moisture.hpp"
#include "gpu_fixture.hpp"
#include "water/moisture_diffusion.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

const Rect kBox = Rect::from_size(1.0, 1.0);

/// 2 000 random points with a wet disc (saturated in its middle 10 cm, falling to 0.3 at its
/// 15 cm rim) in dry sand.
Tin wet_patch_terrain() {
    Tin tin = Tin::random_points(kBox, 2000, 29, [](Vec2 p) { return 0.02 * p.x; });
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = length(va.position[v] - Vec2{0.5, 0.5});
        if (r < 0.15)
            tin.set_moisture(VertexId{v},
                             static_cast<float>(r < 0.1 ? 1.0 : 0.3 + 7.0 * (0.15 - r)));
    }
    return tin;
}

/// sum(A m) over the live vertices, from the terrain's floats.
double cpu_total(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    double sum = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) sum += va.lumped_area[v] * static_cast<double>(va.moisture[v]);
    return sum;
}

class GpuMoistureTest : public GpuTest {};

TEST_F(GpuMoistureTest, SpreadsAndDriesAsTheCpuReferenceDoes) {
    // D = 1e-5 m²/s spreads across a few cells per second; a 10-minute half-life dries
    // visibly. Each call lasts half the GPU's sub-step, so both take it as one sub-step of
    // the same length (the CPU's report says so) and must agree to float rounding.
    MoistureSettings s;
    s.diffusivity = 1e-5;
    s.drying_half_life = 600.0;
    Tin cpu = wet_patch_terrain();
    Tin gpu_tin = wet_patch_terrain();
    TinMirror mirror(ctx(), gpu_tin);
    GpuMoisture gpu(mirror, s);
    const double step = gpu.sub_step();
    ASSERT_TRUE(std::isfinite(step));
    ASSERT_GT(step, 0.0);
    const double seconds = 0.5 * step;
    double moved = 0.0;
    for (int call = 0; call < 60; ++call) {
        const MoistureReport r = spread_and_dry_moisture(cpu, seconds, s);
        ASSERT_EQ(r.sub_steps, 1u) << "call " << call;
        const GpuMoistureRun g = gpu.run(seconds);
        ASSERT_EQ(g.sub_steps, 1u);
    }
    const std::vector<float> m = gpu.read_moisture();
    const std::vector<float> start = wet_patch_terrain().vertices().moisture;
    const VertexArrays& va = cpu.vertices();
    double worst = 0.0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        worst = std::max(worst, std::abs(static_cast<double>(m[v] - va.moisture[v])));
        moved = std::max(moved, std::abs(static_cast<double>(va.moisture[v] - start[v])));
    }
    std::printf("moisture moved up to %.3g; GPU - CPU at most %.3g\n", moved, worst);
    EXPECT_GT(moved, 0.05);  // the moisture did move: the comparison means something
    // Measured 1.8e-6: floats (an ulp of 6e-8 at 1) over 60 sub-steps.
    EXPECT_LE(worst, 5e-6) << "largest GPU - CPU moisture difference";
    // The GPU's moisture handed back to its terrain: the same totals as the CPU's.
    EXPECT_GT(gpu.copy_moisture_into(gpu_tin), 0u);
    EXPECT_NEAR(cpu_total(gpu_tin), cpu_total(cpu), 1e-6 * cpu_total(cpu));
}

TEST_F(GpuMoistureTest, WithoutDryingTheMoistureIsKeptAndStaysWithinItsRange) {
    MoistureSettings s;
    s.diffusivity = 1e-5;
    s.drying_half_life = std::numeric_limits<double>::infinity();
    Tin tin = wet_patch_terrain();
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    const double before = gpu.total();
    ASSERT_GT(before, 0.0);
    // Long calls: many sub-steps each, the stiffest vertices slowed.
    std::size_t sub_steps = 0;
    for (int call = 0; call < 5; ++call)
        sub_steps += gpu.run(40.0 * gpu.sub_step()).sub_steps;
    EXPECT_GE(sub_steps, 200u);
    const double after = gpu.total();
    EXPECT_NEAR(after, before, 1e-5 * before);
    const std::vector<float> m = gpu.read_moisture();
    const VertexArrays& va = tin.vertices();
    float lo = 1.0f, hi = 0.0f;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        lo = std::min(lo, m[v]);
        hi = std::max(hi, m[v]);
    }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_LT(hi, 1.0f);  // the saturated middle has given some to the dry sand
}

TEST_F(GpuMoistureTest, CellsStifferThanTheSubStepAreSlowedAndNeverOvershoot) {
    // A moisture step (saturated inside 12 cm, dry outside) with slivers on it: points 0.1 mm
    // from vertices near the step, whose cells are far below the sub-step's bound. Unslowed,
    // an explicit step would throw their moisture past 1 or below 0.
    MoistureSettings s;
    s.diffusivity = 1e-5;
    s.drying_half_life = std::numeric_limits<double>::infinity();
    Tin tin = Tin::random_points(kBox, 2000, 31);
    std::vector<Vec2> near_step;
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        const double r = length(va.position[v] - Vec2{0.5, 0.5});
        if (va.alive[v] && std::abs(r - 0.12) < 0.02) near_step.push_back(va.position[v]);
    }
    ASSERT_GT(near_step.size(), 20u);
    // 8 of them: fewer than the 1 % of the vertices the sub-step may leave behind.
    for (std::size_t k = 0; k < 8; ++k)
        tin.insert_point(near_step[k] + Vec2{1e-4, 0.7e-4}, 0.0);
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v] && length(va.position[v] - Vec2{0.5, 0.5}) < 0.12)
            tin.set_moisture(VertexId{v}, 1.0f);
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    const double before = gpu.total();
    uint64_t slowed = 0;
    for (int call = 0; call < 10; ++call) {
        const GpuMoistureRun r = gpu.run(20.0 * gpu.sub_step());
        slowed += r.vertices_slowed;
        const std::vector<float> m = gpu.read_moisture();
        for (std::size_t v = 0; v < va.size(); ++v) {
            if (!va.alive[v]) continue;
            ASSERT_GE(m[v], -1e-6f) << "vertex " << v << " after call " << call;
            ASSERT_LE(m[v], 1.0f + 1e-6f) << "vertex " << v << " after call " << call;
        }
    }
    EXPECT_GT(slowed, 0u);
    EXPECT_NEAR(gpu.total(), before, 1e-5 * before);
}

TEST_F(GpuMoistureTest, DryingAloneIsTheExactDecay) {
    MoistureSettings s;
    s.diffusivity = 0.0;
    s.drying_half_life = 100.0;
    Tin tin = wet_patch_terrain();
    const std::vector<float> start = tin.vertices().moisture;
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    gpu.run(150.0);  // 1.5 half-lives: m 2^-1.5
    const std::vector<float> m = gpu.read_moisture();
    const VertexArrays& va = tin.vertices();
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        EXPECT_NEAR(m[v], static_cast<double>(start[v]) * std::exp2(-1.5), 1e-6) << v;
    }
}

TEST_F(GpuMoistureTest, ADryTerrainCostsNoDispatchAndDryingOutEndsTheWork) {
    MoistureSettings s;
    s.drying_half_life = 60.0;
    Tin tin = Tin::random_points(kBox, 500, 3);
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    EXPECT_FALSE(gpu.active());
    EXPECT_EQ(gpu.run(3600.0).sub_steps, 0u);
    tin.set_height(VertexId{10}, 0.02);  // an edit that wets nothing
    EXPECT_EQ(gpu.run(3600.0).dispatches, 0u);
    EXPECT_EQ(gpu.dispatches_recorded(), 0u);
    // Moisture from the CPU wakes it; a day at a one-minute half-life dries it out, and then
    // the work stops.
    tin.set_moisture(VertexId{10}, 0.8f);
    const GpuMoistureRun wet = gpu.run(1.0);
    EXPECT_GT(wet.dispatches, 0u);
    EXPECT_GT(wet.wet, 0u);
    const GpuMoistureRun dried = gpu.run(86400.0);
    EXPECT_EQ(dried.wet, 0u);
    EXPECT_FALSE(gpu.active());
    const uint64_t spent = gpu.dispatches_recorded();
    EXPECT_EQ(gpu.run(3600.0).sub_steps, 0u);
    EXPECT_EQ(gpu.dispatches_recorded(), spent);
}

TEST_F(GpuMoistureTest, WaterWetsTheSandUnderItWhereItIsDeepEnough) {
    MoistureSettings s;
    s.diffusivity = 0.0;
    s.drying_half_life = std::numeric_limits<double>::infinity();
    Tin tin = Tin::random_points(kBox, 800, 5);
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v] && va.position[v].x < 0.5)
            tin.set_water_depth(VertexId{v}, va.position[v].y < 0.5 ? 0.002 : 0.0005);
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    const WettingByWater wetting{0.001, 0.9f};
    gpu.run(0.0, &wetting);
    const std::vector<float> m = gpu.read_moisture();
    int wetted = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const bool deep = va.water_depth[v] >= 0.001;
        EXPECT_EQ(m[v], deep ? 0.9f : 0.0f) << v;
        wetted += deep ? 1 : 0;
    }
    EXPECT_GT(wetted, 50);
}

TEST_F(GpuMoistureTest, KeepsTheMoistureAcrossARetriangulation) {
    MoistureSettings s;
    s.diffusivity = 1e-5;
    s.drying_half_life = std::numeric_limits<double>::infinity();
    Tin tin = wet_patch_terrain();
    TinMirror mirror(ctx(), tin);
    GpuMoisture gpu(mirror, s);
    gpu.run(10.0 * gpu.sub_step());
    gpu.copy_moisture_into(tin);
    const double coarse_step = gpu.sub_step();
    // Twenty points inserted in the wet patch: new, smaller cells.
    for (int k = 0; k < 20; ++k)
        tin.insert_point({0.45 + 0.005 * k, 0.5 + 0.002 * k}, 0.01);
    const double fine_step = gpu.sub_step();  // syncs: the weights follow the new triangles
    std::printf("sub-step %.3g s before, %.3g s after the insertions\n", coarse_step, fine_step);
    EXPECT_LT(fine_step, coarse_step);  // the weights followed the new, smaller cells
    const double before = gpu.total();
    EXPECT_NEAR(before, cpu_total(tin), 1e-6 * before);
    gpu.run(10.0 * fine_step);
    EXPECT_NEAR(gpu.total(), before, 1e-5 * before);
}

TEST_F(GpuMoistureTest, RefusesBadSettingsAndTimes) {
    Tin tin = Tin::random_points(kBox, 100, 1);
    TinMirror mirror(ctx(), tin);
    MoistureSettings bad;
    bad.diffusivity = -1.0;
    EXPECT_THROW(GpuMoisture(mirror, bad), GpuError);
    bad.diffusivity = 1e-7;
    bad.drying_half_life = 0.0;
    EXPECT_THROW(GpuMoisture(mirror, bad), GpuError);
    GpuMoisture gpu(mirror);
    EXPECT_THROW(gpu.run(-1.0), GpuError);
    EXPECT_THROW(gpu.run(std::nan("")), GpuError);
    const WettingByWater wrong{0.0, 1.0f};
    EXPECT_THROW(gpu.run(1.0, &wrong), GpuError);
}

}  // namespace
}  // namespace sandtin::gpu
