// The renderer's baked normal map (TerrainNormalMap over gpu/SurfaceMaps) on a headless Vulkan
// context with the validation layer: after a stamp, only the texels inside the re-baked
// rectangle change, and the incrementally updated map equals a full bake of the new terrain
// from a fresh mirror (the independent oracle); the map is a unit-normal field that matches an
// analytic tilted plane.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "gpu/gpu_error.hpp"
#include "gpu/render/normal_map.hpp"
#include "gpu/tin_mirror.hpp"
#include "gpu/vulkan_context.hpp"
#include "tin/tin.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::render {
namespace {

class NormalMap : public ::testing::Test {
  protected:
    void SetUp() override {
        try {
            gpu::ContextOptions o;
            o.validation = true;
            ctx_ = std::make_unique<gpu::VulkanContext>(o);
        } catch (const gpu::GpuUnavailable& e) {
            GTEST_SKIP() << e.what();
        }
    }
    void TearDown() override {
        if (!ctx_) return;
        EXPECT_EQ(ctx_->validation_message_count(), 0u);
        for (const std::string& m : ctx_->validation_messages())
            ADD_FAILURE() << "validation: " << m;
    }
    std::unique_ptr<gpu::VulkanContext> ctx_;
};

double dunes(Vec2 p) {
    return 0.05 + 0.015 * std::sin(9.0 * p.x + 3.0 * std::sin(4.0 * p.y)) + 0.005 * p.y;
}

TEST_F(NormalMap, ARebakeChangesOnlyItsRectangleAndEqualsAFullBake) {
    const Rect domain{{0, 0}, {1, 1}};
    Tin tin = Tin::random_points(domain, 4000, 11, dunes);
    gpu::TinMirror mirror(*ctx_, tin);
    mirror.sync();
    tin.take_changes();  // the stroke's changes alone, next
    TerrainNormalMap map(mirror, domain, 256);
    ASSERT_EQ(map.grid().width, 256u);
    const std::vector<float> before = map.read_back();

    // A ball stroke: re-triangulation (constraints, new vertices) and new heights.
    SculptContext context(domain);
    StrokeSettings ss;
    ss.depth = 0.012;
    apply_stroke(tin, Tool::build(load_tool_asset("ball")),
                 std::vector<Vec2>{{0.30, 0.60}, {0.42, 0.66}}, ss, context);
    const ChangeSet changes = tin.take_changes();
    mirror.sync();
    const std::optional<gpu::TexelRect> t = map.rebake(tin, changes);
    ASSERT_TRUE(t.has_value());
    const std::vector<float> after = map.read_back();

    gpu::TinMirror fresh_mirror(*ctx_, tin);
    fresh_mirror.sync();
    const TerrainNormalMap fresh(fresh_mirror, domain, 256);
    const std::vector<float> oracle = fresh.read_back();

    const std::uint32_t w = map.grid().width, h = map.grid().height;
    std::size_t changed = 0, changed_outside = 0;
    double worst = 0.0;
    for (std::uint32_t row = 0; row < h; ++row) {
        for (std::uint32_t col = 0; col < w; ++col) {
            const std::size_t i = 4 * (std::size_t{row} * w + col);
            const bool inside =
                col >= t->col0 && col <= t->col1 && row >= t->row0 && row <= t->row1;
            bool differs = false;
            for (std::size_t c = 0; c < 3; ++c) {
                differs |= after[i + c] != before[i + c];
                worst =
                    std::max(worst, static_cast<double>(std::abs(after[i + c] - oracle[i + c])));
            }
            changed += differs ? 1 : 0;
            changed_outside += differs && !inside ? 1 : 0;
        }
    }
    EXPECT_EQ(changed_outside, 0u) << "texels outside the re-baked rectangle changed";
    EXPECT_GT(changed, 200u) << "the stroke changed no texel";
    // The stroke and its rim span about 0.2 x 0.15 m; the rectangle adds the 2-ring around it
    // (edges up to ~4 cm on 4000 random points), so it covers ~0.4 x 0.35 m, not the domain.
    std::printf("re-baked texels %u..%u x %u..%u, %zu changed\n", t->col0, t->col1, t->row0,
                t->row1, changed);
    EXPECT_LT(static_cast<double>(t->width()) * t->height(), 0.25 * w * h);
    EXPECT_LT(worst, 1e-4) << "the incremental map differs from a full bake";
    // Nothing changed: nothing to re-bake.
    EXPECT_FALSE(map.rebake(tin, tin.take_changes()).has_value());
}

TEST_F(NormalMap, ATiltedPlaneBakesItsAnalyticNormalEverywhere) {
    const Rect domain{{-1, 2}, {3, 4}};  // not at the origin, 2:1
    const double gx = 0.3, gy = -0.2;
    Tin tin = Tin::random_points(domain, 500, 5, [&](Vec2 p) { return gx * p.x + gy * p.y; });
    gpu::TinMirror mirror(*ctx_, tin);
    mirror.sync();
    const TerrainNormalMap map(mirror, domain, 128);
    ASSERT_EQ(map.grid().width, 128u);
    ASSERT_EQ(map.grid().height, 64u);
    const std::vector<float> texels = map.read_back();
    const double len = std::sqrt(gx * gx + gy * gy + 1.0);
    for (std::size_t i = 0; i < map.grid().size(); ++i) {
        // 16-bit storage: 3e-5 per component.
        ASSERT_NEAR(texels[4 * i], -gx / len, 1e-4) << "texel " << i;
        ASSERT_NEAR(texels[4 * i + 1], -gy / len, 1e-4) << "texel " << i;
        ASSERT_NEAR(texels[4 * i + 2], 1.0 / len, 1e-4) << "texel " << i;
    }
}

}  // namespace
}  // namespace sandtin::render
