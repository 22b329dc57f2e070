// The physics seam (physics/terrain_solver.hpp) as its callers use it: the editor and the
// script runner hold a RelaxationSolver from make_relaxation_solver and never ask what it is.
// Oracles: the CPU reference through the same interface, the angle of repose, and the
// solver's own feed (what wakes it must not depend on who synced the mirror).

#include <cmath>
#include <memory>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "gpu/make_relaxation_solver.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "physics/physics_oracles.hpp"
#include "tools/sand.hpp"
#include "tools/stamp.hpp"
#include "tools/tool.hpp"

namespace sandtin::gpu {
namespace {

using test::steepest_edge_ratio;
using testing::GpuTest;
using testing::kUnitSquare;

Tin seam_scene() {
    return Tin::random_points(
        kUnitSquare, 4000, 43, [](Vec2 p) { return 0.2 + 0.05 * p.x; },
        TinOptions{.track_changes = false});
}

/// A deep print with vertical walls: far steeper than any angle of repose.
void dig_hole(Tin& tin) {
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = false;
    ToolSpec spec;
    spec.radius = 0.1;
    ASSERT_TRUE(
        stamp(tin, Tool::build(spec), ToolPlacement{{0.5, 0.5}, 0.0, 0.12}, context).applied);
}

TalusSettings jacobi() {
    TalusSettings s;
    s.schedule = Schedule::Jacobi;
    return s;
}

double sand_tan_alpha() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

/// The steepest a rested edge may be, relative to repose: the settle margin (sand stops a
/// little above repose instead of creeping for ever) plus float rounding.
double rest_limit() {
    return 1.0 + jacobi().parameters.settle_margin + 1e-3;
}

TEST_F(GpuTest, TheFactoryGivesEachDeviceItsSolverBehindOneInterface) {
    Tin tin = seam_scene();
    const auto cpu = make_relaxation_solver(tin, MaterialTable::presets(), jacobi(),
                                            RelaxationPlacement{.device = SolverDevice::Cpu});
    EXPECT_EQ(cpu->device(), SolverDevice::Cpu);
    EXPECT_TRUE(cpu->conserves_volume_exactly());
    EXPECT_EQ(cpu->device_dispatches(), 0u);
    Tin other = seam_scene();
    const auto gpu =
        make_relaxation_solver(other, MaterialTable::presets(), jacobi(),
                               RelaxationPlacement{.device = SolverDevice::Gpu, .context = &ctx()});
    EXPECT_EQ(gpu->device(), SolverDevice::Gpu);
    EXPECT_FALSE(gpu->conserves_volume_exactly());
    // The GPU without a device, or on a mirror of another terrain, is a clear error.
    try {
        (void)make_relaxation_solver(tin, MaterialTable::presets(), jacobi(),
                                     RelaxationPlacement{.device = SolverDevice::Gpu});
        ADD_FAILURE() << "no error without a context";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("Vulkan context"), std::string::npos) << e.what();
    }
    TinMirror mirror_of_other(ctx(), other);
    EXPECT_THROW((void)make_relaxation_solver(
                     tin, MaterialTable::presets(), jacobi(),
                     RelaxationPlacement{.device = SolverDevice::Gpu, .mirror = &mirror_of_other}),
                 std::invalid_argument);
}

TEST_F(GpuTest, BothSolversRestADugHoleAtReposeThroughTheInterface) {
    const double tan_alpha = sand_tan_alpha();
    for (const SolverDevice device : {SolverDevice::Cpu, SolverDevice::Gpu}) {
        Tin tin = seam_scene();
        std::unique_ptr<RelaxationSolver> solver =
            make_relaxation_solver(tin, MaterialTable::presets(), jacobi(),
                                   RelaxationPlacement{.device = device, .context = &ctx()});
        dig_hole(tin);
        EXPECT_GT(steepest_edge_ratio(tin, tan_alpha), 3.0) << "the walls are steep";
        const double volume = tin.volume();
        const PhysicsStepReport r = solver->run_to_rest(20000);
        EXPECT_TRUE(r.at_rest) << to_string(device);
        EXPECT_TRUE(solver->at_rest());
        EXPECT_GT(r.volume_moved, 0.0);
        // At rest means at the angle of repose (to the settle margin and float rounding).
        EXPECT_LT(steepest_edge_ratio(tin, tan_alpha), rest_limit()) << to_string(device);
        EXPECT_NEAR(tin.volume(), volume, solver->conserves_volume_exactly() ? 1e-12 : 1e-7);
        if (device == SolverDevice::Gpu) {
            EXPECT_GT(solver->device_dispatches(), 0u);
        }
        EXPECT_TRUE(tin.check_valid().ok());
    }
}

// The editor's terrain view syncs the mirror (to bake its normal map) between the solver's
// steps. The solver wakes from its own feed of the TIN's changes, so what the view took does
// not hide an edit from it: the terrain is the one a solver alone with its mirror gives.
TEST_F(GpuTest, ASolverOnASharedMirrorSeesEditsWhoeverSyncedTheMirrorFirst) {
    Tin alone = seam_scene();
    Tin shared = seam_scene();
    TinMirror own(ctx(), alone);
    TinMirror view_mirror(ctx(), shared);
    const auto a =
        make_relaxation_solver(alone, MaterialTable::presets(), jacobi(),
                               RelaxationPlacement{.device = SolverDevice::Gpu, .mirror = &own});
    const auto b = make_relaxation_solver(
        shared, MaterialTable::presets(), jacobi(),
        RelaxationPlacement{.device = SolverDevice::Gpu, .mirror = &view_mirror});
    a->run_to_rest(100);
    b->run_to_rest(100);
    dig_hole(alone);
    dig_hole(shared);
    const SyncStats taken = view_mirror.sync();  // the view, before the solver steps
    EXPECT_GT(taken.vertex_ranges, 0u) << "the view's sync took the dig";
    const PhysicsStepReport ra = a->run_to_rest(20000);
    const PhysicsStepReport rb = b->run_to_rest(20000);
    EXPECT_GT(rb.volume_moved, 0.0) << "the solver slept through the dig";
    EXPECT_EQ(ra.iterations, rb.iterations);
    ASSERT_EQ(alone.vertex_capacity(), shared.vertex_capacity());
    const VertexArrays& x = alone.vertices();
    const VertexArrays& y = shared.vertices();
    for (std::uint32_t v = 0; v < x.size(); ++v) {
        ASSERT_EQ(x.alive[v], y.alive[v]) << v;
        if (x.alive[v]) {
            ASSERT_EQ(x.height[v], y.height[v]) << v;
        }
    }
    EXPECT_LT(steepest_edge_ratio(shared, sand_tan_alpha()), rest_limit());
}

}  // namespace
}  // namespace sandtin::gpu
