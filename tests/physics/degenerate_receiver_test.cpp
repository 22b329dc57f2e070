// Vertical slivers (vertices with next to no area in the plane, between constraints a hair
// apart) take nothing (kDegenerateAreaRatio, engine/physics/talus_kernel.hpp): the sand above
// them used to creep through them forever, since whatever one received it passed on at once.

#include <gtest/gtest.h>

#include <cmath>

#include "physics/sand_physics.hpp"
#include "physics_oracles.hpp"
#include "support/slivers.hpp"

namespace sandtin {
namespace {

TEST(DegenerateReceivers, VerticalSliversDoNotKeepTheSandCreeping) {
    test::SliverScene s = test::vertical_sliver_scene(2000, 5);
    Tin& tin = s.tin;
    const VertexArrays& va = tin.vertices();
    ASSERT_TRUE(tin.check_valid().ok());
    ASSERT_GE(test::sliver_vertices(tin), s.middle.size()) << "the scene has no slivers";

    SandPhysics physics(tin, MaterialTable::presets(), {});
    physics.activate_all();
    const double before = tin.volume();
    const PhysicsStepReport r = physics.run_to_rest(20000);
    RecordProperty("iterations", r.iterations);
    EXPECT_TRUE(r.at_rest) << physics.active_count() << " vertices still active";
    EXPECT_NEAR(tin.volume(), before, 1e-12 * std::abs(before));
    // Every edge but those into the slivers rests at the angle of repose.
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    const double steepest = test::steepest_edge_ratio(
        tin, tan_alpha, [&](std::uint32_t v) { return va.height[v]; },
        [&](std::uint32_t v, std::uint32_t w) { return test::joins_sliver(va, v, w); });
    EXPECT_LE(steepest, 1.0 + 1e-3);
    EXPECT_TRUE(tin.check_valid().ok());
}

}  // namespace
}  // namespace sandtin
