// Direct dispatches larger than one row of workgroups: the grid arithmetic, and kernels run on
// a context whose rows are capped at 3 groups giving the same bits as on the device's own
// limit (so a 2-D grid reaches every thread exactly once in every kernel that is dispatched
// directly: normals, bake, seeding and packing).

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "gpu/dispatch_grid.hpp"
#include "gpu/gpu_sand_physics.hpp"
#include "gpu/surface_maps.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "maps/map_grid.hpp"
#include "physics/sand_physics.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;
using testing::kUnitSquare;

TEST(DispatchGrid, OneRowWhenItFitsElseFullRowsThatCoverEveryGroup) {
    EXPECT_EQ(dispatch_grid(1, 65535, 65535)->x, 1u);
    EXPECT_EQ(dispatch_grid(1, 65535, 65535)->y, 1u);
    EXPECT_EQ(dispatch_grid(65535, 65535, 65535)->y, 1u);
    const DispatchGrid two = *dispatch_grid(65536, 65535, 65535);
    EXPECT_EQ(two.x, 65535u);
    EXPECT_EQ(two.y, 2u);
    // Every count up to a few rows: enough groups, and no row that is wholly idle.
    for (uint32_t groups = 1; groups <= 40; ++groups) {
        const DispatchGrid g = *dispatch_grid(groups, 7, 100);
        EXPECT_LE(g.x, 7u);
        EXPECT_GE(uint64_t{g.x} * g.y, groups);
        EXPECT_LT(uint64_t{g.x} * (g.y - 1), groups);
    }
    // The largest count of 64-thread groups (UINT32_MAX threads) fits the minimum limits.
    const uint32_t most = (UINT32_MAX - 1) / 64 + 1;
    ASSERT_TRUE(dispatch_grid(most, 65535, 65535).has_value());
    EXPECT_FALSE(dispatch_grid(7 * 100 + 1, 7, 100).has_value());
    EXPECT_FALSE(dispatch_grid(5, 0, 100).has_value());
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST_F(GpuTest, KernelsGiveTheSameBitsWhenTheirGroupsGoInRows) {
    ContextOptions options;
    options.validation = true;
    options.max_dispatch_groups_x = 3;  // 192 threads a row: every dispatch here is 2-D
    VulkanContext rows(options);
    ASSERT_EQ(rows.dispatch_groups_x(), 3u);

    struct Result {
        std::vector<Vec3> vertex_normals, corner_normals;
        std::vector<double> height_map, normal_map;
        std::vector<double> heights;
    };
    const auto run = [](VulkanContext& c) {
        Result r;
        Tin tin = Tin::random_points(kUnitSquare, 20000, 31,
                                     [](Vec2 p) { return testing::collapsing_cone(p); });
        TinMirror mirror(c, tin);
        mirror.sync();
        SurfaceMaps maps(mirror);
        maps.compute_normals();
        r.vertex_normals = maps.read_vertex_normals();
        r.corner_normals = maps.read_corner_normals();
        const BakedMaps baked = maps.bake(MapGrid(kUnitSquare, 96, 64, SampleAt::Centres));
        r.height_map = baked.height.values;
        r.normal_map = baked.normal.values;
        // Relaxation: seeding every vertex and packing the touched ones are direct dispatches.
        TalusSettings settings;
        settings.schedule = Schedule::Jacobi;
        GpuSandPhysics physics(tin, c, MaterialTable::presets(), settings);
        physics.activate_all();
        physics.step(50);
        const VertexArrays& va = tin.vertices();
        r.heights.assign(va.height.begin(), va.height.end());
        return r;
    };
    const Result capped = run(rows);
    const Result device = run(ctx());
    EXPECT_TRUE(same_bits(capped.vertex_normals, device.vertex_normals));
    EXPECT_TRUE(same_bits(capped.corner_normals, device.corner_normals));
    EXPECT_TRUE(same_bits(capped.height_map, device.height_map));
    EXPECT_TRUE(same_bits(capped.normal_map, device.normal_map));
    EXPECT_TRUE(same_bits(capped.heights, device.heights));
    // The cone is far steeper than repose, so the relaxation moved sand and the heights
    // compare something.
    EXPECT_NE(capped.heights, Tin::random_points(kUnitSquare, 20000, 31,
                                                 [](Vec2 p) { return testing::collapsing_cone(p); })
                                  .vertices()
                                  .height);
    EXPECT_EQ(rows.validation_message_count(), 0u);
}

}  // namespace
}  // namespace sandtin::gpu
