// Vertical slivers (vertices with next to no area in the plane, between constraints a hair
// apart) take nothing (kDegenerateAreaRatio, engine/physics/talus_kernel.hpp): the sand above
// them used to creep through them forever, since whatever one received it passed on at once.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/sand_physics.hpp"
#include "support/sliver_scene.hpp"

namespace sandtin {
namespace {

TEST(DegenerateReceivers, VerticalSliversDoNotKeepTheSandCreeping) {
    test::SliverScene s = test::vertical_sliver_scene(2000, 5);
    Tin& tin = s.tin;
    const VertexArrays& va = tin.vertices();
    ASSERT_TRUE(tin.check_valid().ok());
    for (VertexId v : s.middle)
        ASSERT_LT(va.lumped_area[v.value], 1e-9) << "the scene has no sliver at " << v.value;

    SandPhysics physics(tin, MaterialTable::presets(), {});
    physics.activate_all();
    const double before = tin.volume();
    const PhysicsStepReport r = physics.run_to_rest(20000);
    RecordProperty("iterations", r.iterations);
    EXPECT_TRUE(r.at_rest) << physics.active_count() << " vertices still active";
    EXPECT_NEAR(tin.volume(), before, 1e-12 * std::abs(before));
    // Every edge but those into the slivers rests at the angle of repose.
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    std::vector<VertexId> ring;
    double steepest = 0.0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        tin.neighbours(VertexId{v}, ring);
        for (VertexId w : ring) {
            const double av = va.lumped_area[v], aw = va.lumped_area[w.value];
            if (aw < kDegenerateAreaRatio * av || av < kDegenerateAreaRatio * aw) continue;
            const double run = distance(va.position[v], va.position[w.value]) * tan_alpha;
            steepest = std::max(steepest, (va.height[v] - va.height[w.value]) / run);
        }
    }
    EXPECT_LE(steepest, 1.0 + 1e-3);
    EXPECT_TRUE(tin.check_valid().ok());
}

}  // namespace
}  // namespace sandtin
