// What the renderer draws from is the mesh, byte for byte, on a headless Vulkan context with the
// validation layer. The case that once showed "broken glass" in the editor: a smaller terrain
// replaces a larger one, whose buffers are big enough to keep, and then grows; the grown tail
// was never uploaded, so the GPU drew the old terrain's triangles there.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/render/terrain_renderer.hpp"
#include "gpu/vk_handle.hpp"
#include "gpu/vulkan_context.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::render {
namespace {

class Renderer : public ::testing::Test {
  protected:
    void SetUp() override {
        try {
            gpu::ContextOptions o;
            o.validation = true;
            ctx_ = std::make_unique<gpu::VulkanContext>(o);
        } catch (const gpu::GpuUnavailable& e) {
            GTEST_SKIP() << e.what();
        }
        // The render pass the renderer's pipelines are made for: a colour and a depth target,
        // as the editor's swapchain has.
        VkAttachmentDescription attachments[2]{};
        attachments[0].format = VK_FORMAT_B8G8R8A8_SRGB;
        attachments[1].format = VK_FORMAT_D32_SFLOAT;
        for (VkAttachmentDescription& a : attachments) {
            a.samples = VK_SAMPLE_COUNT_1_BIT;
            a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        }
        attachments[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        const VkAttachmentReference colour{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        const VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkSubpassDescription subpass{};
        subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subpass.colorAttachmentCount = 1;
        subpass.pColorAttachments = &colour;
        subpass.pDepthStencilAttachment = &depth;
        VkRenderPassCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
        info.attachmentCount = 2;
        info.pAttachments = attachments;
        info.subpassCount = 1;
        info.pSubpasses = &subpass;
        VkRenderPass pass = VK_NULL_HANDLE;
        ASSERT_EQ(vkCreateRenderPass(ctx_->device(), &info, nullptr, &pass), VK_SUCCESS);
        pass_ = gpu::UniqueRenderPass(ctx_->device(), pass);
    }
    void TearDown() override {
        if (!ctx_) return;
        EXPECT_EQ(ctx_->validation_message_count(), 0u);
        for (const std::string& m : ctx_->validation_messages())
            ADD_FAILURE() << "validation: " << m;
    }

    /// The renderer draws exactly the mesh: its vertex and index buffers hold the mesh's
    /// arrays, every byte of them.
    static void expect_draws(const TerrainRenderer& renderer, const TerrainMesh& mesh) {
        const auto v = renderer.drawn_vertex_bytes();
        const auto i = renderer.drawn_index_bytes();
        ASSERT_EQ(v.size(), mesh.vertices().size() * sizeof(RenderVertex));
        ASSERT_EQ(i.size(), mesh.indices().size() * sizeof(std::uint32_t));
        EXPECT_EQ(std::memcmp(v.data(), mesh.vertices().data(), v.size()), 0);
        std::size_t differing = 0;
        for (std::size_t k = 0; k < mesh.indices().size(); ++k) {
            std::uint32_t drawn = 0;
            std::memcpy(&drawn, i.data() + k * sizeof(std::uint32_t), sizeof(drawn));
            differing += drawn != mesh.indices()[k] ? 1 : 0;
        }
        EXPECT_EQ(differing, 0u) << "of " << mesh.indices().size() << " indices";
    }

    std::unique_ptr<gpu::VulkanContext> ctx_;
    gpu::UniqueRenderPass pass_;
};

TEST_F(Renderer, ASmallerTerrainThatGrowsIsDrawnAsItsMeshWithNothingOfTheLargerOneLeft) {
    TerrainRenderer renderer(*ctx_, pass_.get());
    const Rect domain{{0, 0}, {1, 1}};
    const auto height = [](Vec2 p) { return 0.05 + 0.01 * p.x; };
    Tin big = Tin::random_points(domain, 60000, 3, height);
    TerrainMesh mesh(MaterialTable::presets());
    big.take_changes();
    renderer.upload(mesh, mesh.rebuild(big));
    expect_draws(renderer, mesh);

    // The same mesh and renderer over a terrain a tenth the size, which then grows a little
    // at a time (stamps insert their rims' vertices and triangles past the rebuilt arrays),
    // staying within the buffers the larger terrain left.
    Tin small = Tin::random_points(domain, 6000, 4, height);
    small.take_changes();
    renderer.upload(mesh, mesh.rebuild(small));
    expect_draws(renderer, mesh);
    const std::size_t rebuilt_slots = mesh.indices().size() / 3;
    SculptContext context(domain);
    const Tool tool = Tool::build(load_tool_asset("circle"));
    for (int k = 0; k < 40 && mesh.indices().size() / 3 <= rebuilt_slots; ++k) {
        const Vec2 at{0.1 + 0.02 * k, 0.5};
        stamp(small, tool, {at, 0.0, *small.height_at(at) - 0.005}, context);
        renderer.upload(mesh, mesh.update(small, small.take_changes()));
        expect_draws(renderer, mesh);
    }
    ASSERT_GT(mesh.indices().size() / 3, rebuilt_slots) << "the terrain did not grow";
    ASSERT_LT(mesh.indices().size() / 3, 3 * std::size_t{60000}) << "nor within the old buffers";
    for (int k = 0; k < 3; ++k) {  // and on from there
        const Vec2 at{0.3 + 0.2 * k, 0.3};
        stamp(small, tool, {at, 0.0, *small.height_at(at) - 0.005}, context);
        renderer.upload(mesh, mesh.update(small, small.take_changes()));
        expect_draws(renderer, mesh);
    }

    // Dropped: nothing is drawn until the next rebuild is uploaded.
    renderer.drop_mesh();
    EXPECT_TRUE(renderer.drawn_vertex_bytes().empty());
    EXPECT_TRUE(renderer.drawn_index_bytes().empty());
    TerrainMesh fresh(MaterialTable::presets());
    renderer.upload(fresh, fresh.rebuild(small));
    expect_draws(renderer, fresh);
}

}  // namespace
}  // namespace sandtin::render
