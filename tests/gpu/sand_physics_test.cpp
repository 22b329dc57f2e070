// The run-time physics choice: GPU sand physics against the CPU SandPhysics (Jacobi) on the
// same edits, and the read-back into the TIN.

#include <cmath>

#include "gpu/gpu_sand_physics.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "physics/sand_physics.hpp"
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

}  // namespace
}  // namespace sandtin::gpu
