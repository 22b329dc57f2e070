// The run-time physics choice: GPU sand physics against the CPU SandPhysics (Jacobi) on the
// same edits, and the read-back into the TIN.

#include <cmath>
#include <cstdio>
#include <vector>

#include "gpu/gpu_sand_physics.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "physics/cone.hpp"
#include "physics/face_slopes.hpp"
#include "physics/physics_oracles.hpp"
#include "physics/sand_physics.hpp"
#include "tools/sand.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;
using testing::kUnitSquare;

Tin scene() {
    return Tin::random_points(kUnitSquare, 20000, 41,
                              [](Vec2 p) { return 0.2 + 0.1 * p.x + 0.05 * std::sin(12.0 * p.y); });
}

void dig(Tin& tin) {
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;  // the physics is what is compared
    ToolSpec spec;
    spec.radius = 0.08;
    const Tool tool = Tool::build(spec);
    ASSERT_TRUE(stamp(tin, tool, ToolPlacement{{0.5, 0.5}, 0.0, 0.05}, context).applied);
}

TEST_F(GpuTest, GpuPhysicsMatchesCpuPhysicsAfterAStampAndWritesBackIntoTheTin) {
    // The seeds' rule: float and double agree everywhere (a margin's step at the trigger is
    // tests/gpu/relaxation_test's SettleMarginMatchesCpuJacobi).
    TalusSettings settings = seeds_rule();
    settings.schedule = Schedule::Jacobi;

    Tin cpu_tin = scene();
    SandPhysics cpu(cpu_tin, MaterialTable::presets(), settings);
    Tin gpu_tin = scene();
    GpuSandPhysics gpu(gpu_tin, ctx(), MaterialTable::presets(), settings);

    dig(cpu_tin);
    dig(gpu_tin);
    const double volume_before = gpu_tin.volume();
    ASSERT_EQ(cpu_tin.vertex_capacity(), gpu_tin.vertex_capacity());

    // 300 iterations (this dig keeps a few thousand vertices trickling for thousands of
    // iterations on both schedules; the comparison needs motion, not rest).
    const PhysicsStepReport rc = cpu.step(300);
    std::vector<VertexId> changed;
    const PhysicsStepReport rg = gpu.step(300, &changed);
    EXPECT_EQ(rc.iterations, rg.iterations);
    EXPECT_GT(rg.changed, 0u);
    EXPECT_FALSE(changed.empty());
    // The volume the sand moved, summed in double on the CPU and in float per vertex between
    // read-backs on the GPU (it used to be reported as 0).
    std::printf("volume moved: cpu %.9g gpu %.9g m3\n", rc.volume_moved, rg.volume_moved);
    EXPECT_GT(rc.volume_moved, 0.0);
    EXPECT_NEAR(rg.volume_moved, rc.volume_moved, 1e-4 * rc.volume_moved);

    // The GPU wrote its heights into the TIN: compare the two TINs directly.
    double lo = 1e300, hi = -1e300, worst = 0.0, moved = 0.0;
    const VertexArrays& a = cpu_tin.vertices();
    const VertexArrays& b = gpu_tin.vertices();
    for (uint32_t v = 0; v < a.size(); ++v) {
        if (!a.alive[v]) continue;
        ASSERT_TRUE(b.alive[v]);
        lo = std::min(lo, a.height[v]);
        hi = std::max(hi, a.height[v]);
        worst = std::max(worst, std::abs(a.height[v] - b.height[v]));
    }
    for (VertexId v : changed)
        moved = std::max(moved, std::abs(b.height[v.value] - 0.0));
    EXPECT_GT(moved, 0.0);
    EXPECT_LE(worst, 1e-5 * (hi - lo));
    // Volume: conserved on the GPU to float rounding of the written-back heights.
    EXPECT_NEAR(gpu_tin.volume(), volume_before, 1e-6 * std::abs(volume_before));
    EXPECT_TRUE(gpu_tin.check_valid().ok());
}

// The relocation radius on the GPU (the editor's default r_S is 1 cm): sand poured at one point
// of a two-triangle terrain must grow its own detail and pile up as it does on the CPU, the
// reference (tests/physics/cone_test's TwoTriangleFlatTerrainJacobi pours the same way: 100
// portions, 50 iterations apart). No other GPU test set r_S, and the GPU lost the split
// requests of every batch that moved sand: the pile refined 108 vertices where the CPU refines
// ~400, and stood twice as tall as the cone.
struct PileOnTwoTriangles {
    Tin tin = Tin::from_points(kUnitSquare, std::vector<Vec2>{{0.0, 0.0}, {1.0, 1.0}},
                               std::vector<double>{0.0, 0.0});
    VertexId apex;
    double top = 0.0;    ///< highest vertex (m)
    double reach = 0.0;  ///< farthest vertex holding sand from the centre (m)
    PhysicsStepReport report;
};

/// Runs `run` (a step of `physics` that appends to a list of changed vertices) and checks
/// that every vertex born in it is on that list: the refinement's vertices go to the
/// simplification with the moved ones, whether or not sand reached them (callers queue the list
/// for the simplifier). Returns how many were born.
template <class Run>
std::size_t check_births_reported(const Tin& tin, Run&& run) {
    const std::vector<std::uint8_t> was_alive = tin.vertices().alive;
    std::vector<VertexId> changed;
    run(&changed);
    const VertexArrays& va = tin.vertices();
    std::vector<std::uint8_t> reported(va.size(), 0);
    for (VertexId v : changed)
        reported[v.value] = 1;
    std::size_t born = 0, unreported = 0;
    for (uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || (v < was_alive.size() && was_alive[v])) continue;
        ++born;
        unreported += reported[v] ? 0u : 1u;
    }
    EXPECT_EQ(unreported, 0u) << "of " << born << " vertices the refinement inserted";
    return born;
}

template <class Physics>
void pour_in_portions(PileOnTwoTriangles& p, Physics& physics, double volume) {
    const double before = p.tin.volume();
    constexpr int kPortions = 100;
    std::size_t born = 0;
    for (int k = 0; k < kPortions; ++k) {
        p.tin.set_height(
            p.apex,
            p.tin.height(p.apex) + volume / kPortions / p.tin.vertices().lumped_area[p.apex.value]);
        born += check_births_reported(p.tin, [&](std::vector<VertexId>* changed) {
            p.report.accumulate(physics.step(50, changed));
        });
    }
    born += check_births_reported(p.tin, [&](std::vector<VertexId>* changed) {
        p.report.accumulate(physics.run_to_rest(60000, changed));
    });
    EXPECT_GT(born, 100u);
    const VertexArrays& va = p.tin.vertices();
    for (uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        p.top = std::max(p.top, va.height[v]);
        if (va.height[v] > 1e-4) p.reach = std::max(p.reach, distance(va.position[v], {0.5, 0.5}));
    }
    EXPECT_NEAR(p.tin.volume(), before + volume, 1e-5 * volume);
    EXPECT_TRUE(p.tin.check_valid().ok());
}

/// A pile poured in portions on two triangles with r_S, on the CPU (Jacobi) and on the GPU
/// under `rule`: both rest near the cone and near each other.
void pile_on_cpu_and_gpu(VulkanContext& context, SlopeRule rule) {
    TalusSettings settings;
    settings.schedule = Schedule::Jacobi;
    settings.parameters.relocation_radius = 0.02;
    settings.parameters.rule = rule;
    constexpr double kVolume = 1e-3;
    PileOnTwoTriangles cpu_pile, gpu_pile;
    for (PileOnTwoTriangles* p : {&cpu_pile, &gpu_pile}) {
        // As test::pour_at_point: the point's edges are refined to r_S before sand lands.
        p->apex = p->tin.insert_point_on_surface({0.5, 0.5});
        SandPhysics refiner(p->tin, MaterialTable::presets(), settings);
        const VertexId one[] = {p->apex};
        refiner.refine_around(one);
    }
    SandPhysics cpu(cpu_pile.tin, MaterialTable::presets(), settings);
    pour_in_portions(cpu_pile, cpu, kVolume);
    GpuSandPhysics gpu(gpu_pile.tin, context, MaterialTable::presets(), settings);
    pour_in_portions(gpu_pile, gpu, kVolume);
    // The face rule rests at the true cone, between (1 - m) tan(alpha) (where flowing sand
    // levels to, the settle margin) and tan(alpha): the cone of the former is its reference,
    // as in physics/face_rule_test.cpp. The edge rule's piles stand steeper than their edges.
    const double repose = MaterialTable::presets().at(0).talus_slope(0.0);
    const Cone cone = Cone::from_volume(
        kVolume,
        rule == SlopeRule::Face ? (1.0 - settings.parameters.settle_margin) * repose : repose);
    std::printf(
        "  cpu: vertices %zu, iterations %d, apex %.5f, reach %.5f\n"
        "  gpu: vertices %zu, iterations %d, apex %.5f, reach %.5f (cone %.5f, %.5f)\n",
        cpu_pile.tin.vertex_count(), cpu_pile.report.iterations, cpu_pile.top, cpu_pile.reach,
        gpu_pile.tin.vertex_count(), gpu_pile.report.iterations, gpu_pile.top, gpu_pile.reach,
        cone.height, cone.radius);
    EXPECT_TRUE(cpu_pile.report.at_rest);
    EXPECT_TRUE(gpu_pile.report.at_rest);
    EXPECT_GT(cpu_pile.tin.vertex_count(), 300u);  // the detail came from r_S refinement alone
    EXPECT_NEAR(static_cast<double>(gpu_pile.tin.vertex_count()),
                static_cast<double>(cpu_pile.tin.vertex_count()),
                0.1 * static_cast<double>(cpu_pile.tin.vertex_count()));
    EXPECT_NEAR(gpu_pile.top, cpu_pile.top, 0.03 * cpu_pile.top);
    EXPECT_NEAR(gpu_pile.reach, cpu_pile.reach, 0.1 * cpu_pile.reach);
    // Both near the cone (the reach is the last vertex with sand, a little beyond the toe).
    EXPECT_NEAR(cpu_pile.top, cone.height, 0.05 * cone.height);
    EXPECT_NEAR(gpu_pile.top, cone.height, 0.05 * cone.height);
    if (rule == SlopeRule::Face) {
        // The GPU's pile, written back into its TIN, has no face steeper than repose.
        const FaceSlopeReport faces = measure_face_slopes(gpu_pile.tin, MaterialTable::presets());
        EXPECT_EQ(faces.steep_faces, 0u) << "steepest " << faces.max_ratio;
    }
}

TEST_F(GpuTest, GpuPhysicsWithARelocationRadiusPilesAsTheCpuDoes) {
    pile_on_cpu_and_gpu(ctx(), SlopeRule::Edge);
}

TEST_F(GpuTest, GpuPhysicsUnderTheFaceRulePilesAsTheCpuDoes) {
    pile_on_cpu_and_gpu(ctx(), SlopeRule::Face);
}

TEST_F(GpuTest, GpuPhysicsAtRestRecordsNothingAndUploadsNothing) {
    Tin tin = Tin::random_points(kUnitSquare, 5000, 2, [](Vec2 p) { return 0.1 * p.x; });
    GpuSandPhysics gpu(tin, ctx(), MaterialTable::presets());
    gpu.activate_all();
    const PhysicsStepReport first = gpu.run_to_rest(100);
    EXPECT_TRUE(first.at_rest);
    EXPECT_EQ(first.changed, 0u);
    const uint64_t dispatches = gpu.relaxation().dispatches_recorded();
    const PhysicsStepReport idle = gpu.step(10);
    EXPECT_EQ(idle.iterations, 0);
    EXPECT_EQ(gpu.relaxation().dispatches_recorded(), dispatches);
    EXPECT_EQ(gpu.last_sync_bytes(), 0u);
}

TEST_F(GpuTest, LoweringAVertexWakesTheNeighboursAboveIt) {
    // physics' ActiveSet test of the same name, on the GPU: an outside edit lowers one vertex
    // of a flat terrain at rest. Only its higher neighbours can send sand down the edges it
    // steepened, so they must wake with it.
    Tin tin = Tin::random_points(kUnitSquare, 4000, 8);
    GpuSandPhysics gpu(tin, ctx(), MaterialTable::presets());
    gpu.activate_all();
    ASSERT_TRUE(gpu.run_to_rest(1000).at_rest);  // flat: at rest at once
    const VertexId pit{tin.locate({0.5, 0.5}).corners[0]};
    tin.set_height(pit, -0.02);
    const double volume = tin.volume();
    const PhysicsStepReport r = gpu.run_to_rest(100000);
    EXPECT_TRUE(r.at_rest);
    EXPECT_GT(tin.height(pit), -0.02);
    EXPECT_NEAR(tin.volume(), volume, 1e-6 * 0.02);  // float transfers: 1e-6 of the pit
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    EXPECT_LE(test::steepest_edge_ratio(tin, tan_alpha), 1.0 + 1e-3);
}

TEST_F(GpuTest, SandDrainsToTheBedrockButNeverMovesIt) {
    // 1 mm of sand on a bedrock mound far steeper than repose, at heights float cannot
    // represent (+ i * 1e-9 m): the sand on the slopes drains to the rock and piles at the
    // foot. Every vertex's bedrock in the TIN must come back exactly as it was, with the
    // surface on or above it.
    auto mound = [](Vec2 p) {
        return 0.1 + std::max(0.0, 0.3 - 1.5 * std::hypot(p.x - 0.5, p.y - 0.5));
    };
    Tin tin = Tin::random_points(kUnitSquare, 6000, 17, mound);
    const VertexArrays& va = tin.vertices();
    std::vector<double> rock(va.size(), 0.0);
    for (uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        rock[v] = mound(va.position[v]) + 1e-9 * static_cast<double>(v % 97);
        tin.set_height(VertexId{v}, rock[v] + 0.001);
        tin.set_bedrock(VertexId{v}, rock[v]);
    }
    GpuSandPhysics gpu(tin, ctx(), MaterialTable::presets());
    gpu.activate_all();
    EXPECT_GT(gpu.run_to_rest(20000).volume_moved, 0.0);
    std::size_t bare = 0;
    for (uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || v >= rock.size()) continue;
        ASSERT_EQ(va.bedrock[v], rock[v]) << v;
        ASSERT_GE(va.height[v], va.bedrock[v]) << v;
        bare += va.height[v] - va.bedrock[v] < 1e-4;
    }
    EXPECT_GT(bare, 100u);  // the slopes were drained to the rock
}

TEST_F(GpuTest, AnElevationModelHundredsOfMetresUpRestsAtReposeAsNearZero) {
    // A pour relaxed on flat ground at 500 m and at 0 m. Float heights 500 m up have an ulp
    // of 31 um, which on 1 cm edges is several per cent of the slope: without a height origin
    // the GPU stopped with edges 1.58 times steeper than repose. Both must rest at repose,
    // and be the same pile.
    std::vector<double> piles[2];
    for (const double ground : {0.0, 500.0}) {
        Tin tin = Tin::random_points(kUnitSquare, 20000, 3, [&](Vec2) { return ground; });
        GpuSandPhysics gpu(tin, ctx(), MaterialTable::presets());
        SculptContext context(tin.domain());
        PourSettings pour;
        pour.radius = 0.05;
        pour_sand(tin, {0.5, 0.5}, 2e-4, pour, context);
        ASSERT_TRUE(gpu.run_to_rest(200000).at_rest);
        const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
        EXPECT_LE(test::steepest_edge_ratio(tin, tan_alpha), 1.0 + 1e-3) << ground;
        const VertexArrays& va = tin.vertices();
        for (uint32_t v = 0; v < va.size(); ++v)
            piles[ground > 0.0].push_back(va.alive[v] ? va.height[v] - ground : 0.0);
    }
    ASSERT_EQ(piles[0].size(), piles[1].size());
    double worst = 0.0;
    for (std::size_t i = 0; i < piles[0].size(); ++i)
        worst = std::max(worst, std::abs(piles[0][i] - piles[1][i]));
    EXPECT_LT(worst, 1e-3);  // metres: the same pile, to float rounding along its slopes
}

}  // namespace
}  // namespace sandtin::gpu
