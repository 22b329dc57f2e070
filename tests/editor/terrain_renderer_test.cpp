// What the renderer draws from is the mesh, byte for byte, on a headless Vulkan context with the
// validation layer. The case that once showed "broken glass" in the editor: a smaller terrain
// replaces a larger one, whose buffers are big enough to keep, and then grows; the grown tail
// was never uploaded, so the GPU drew the old terrain's triangles there.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "gpu/gpu_error.hpp"
#include "gpu/render/normal_map.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/render/terrain_renderer.hpp"
#include "gpu/vk_handle.hpp"
#include "gpu/vulkan_context.hpp"
#include "io/session_file.hpp"
#include "terrain_view.hpp"
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

    /// A view with the renderer it draws through and the document it shows.
    struct ViewUnderTest {
        TerrainRenderer& renderer;
        editor::TerrainView& view;
        editor::Document& doc;
    };
    /// Two views of the same terrain draw the same: the same vertex bytes, triangles and
    /// constrained edges, normal maps within `map_tolerance` once both are baked (frames bake a
    /// new one a band an update), and mirrors whose graphs match their TINs.
    void expect_same_view(const ViewUnderTest& a, const ViewUnderTest& b, float map_tolerance) {
        for (const ViewUnderTest* v : {&a, &b}) {
            for (int k = 0; k < 64 && v->view.baking_normal_map(); ++k)
                v->view.update(v->doc, [] {});
            ASSERT_FALSE(v->view.baking_normal_map());
            ASSERT_NE(v->view.normal_map(), nullptr);
            EXPECT_TRUE(v->view.mirror().graph().matches(v->doc.tin()));
        }
        expect_draws(b.renderer, b.view.mesh());
        const auto bytes_a = a.renderer.drawn_vertex_bytes();
        const auto bytes_b = b.renderer.drawn_vertex_bytes();
        ASSERT_EQ(bytes_a.size(), bytes_b.size());
        EXPECT_EQ(std::memcmp(bytes_a.data(), bytes_b.data(), bytes_a.size()), 0);
        EXPECT_EQ(a.view.mesh().indices(), b.view.mesh().indices());
        EXPECT_EQ(a.view.mesh().constrained_edges(), b.view.mesh().constrained_edges());
        const std::vector<float> map_a = a.view.normal_map()->read_back();
        const std::vector<float> map_b = b.view.normal_map()->read_back();
        ASSERT_EQ(map_a.size(), map_b.size());
        float worst = 0.0f;
        for (std::size_t k = 0; k < map_a.size(); ++k)
            worst = std::max(worst, std::abs(map_a[k] - map_b[k]));
        EXPECT_LE(worst, map_tolerance);
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

// The editor opens a scene on a worker thread and prepares its view there (the render mesh,
// the GPU mirror's graph and flags, the contrast range), so the UI thread only uploads. A view
// built from that draws the same bytes, bakes the same normal map and mirrors the same graph as
// a view built whole on the UI thread; and when the terrain moved on between the preparation
// and the upload, it catches up instead of showing the stale terrain.
TEST_F(Renderer, AViewPreparedOnAWorkerDrawsWhatAViewBuiltWholeDraws) {
    // A scene with a tool's constrained rim, saved and opened twice.
    const Rect domain{{0, 0}, {1, 1}};
    Tin tin = Tin::random_points(domain, 5000, 7, [](Vec2 p) { return 0.05 + 0.02 * p.x * p.y; });
    SculptContext context(domain);
    const Tool tool = Tool::build(load_tool_asset("circle"));
    stamp(tin, tool, {{0.4, 0.5}, 0.3, *tin.height_at({0.4, 0.5}) - 0.01}, context);
    const std::filesystem::path scene =
        std::filesystem::temp_directory_path() / "sandtin-prepared-view.sandtin";
    save_session(scene, Session{tin.snapshot(), context.peek_generation(), "{}", {}});
    editor::Document whole = editor::Document::open(scene);
    editor::Document prepared = editor::Document::open(scene);
    std::filesystem::remove(scene);

    TerrainRenderer whole_renderer(*ctx_, pass_.get());
    TerrainRenderer prepared_renderer(*ctx_, pass_.get());
    editor::TerrainView whole_view(*ctx_, whole_renderer);
    editor::TerrainView prepared_view(*ctx_, prepared_renderer);
    whole_view.rebuild(whole);
    std::optional<editor::PreparedView> made;
    std::thread worker([&] { made.emplace(editor::TerrainView::prepare(prepared, *ctx_)); });
    worker.join();
    ASSERT_TRUE(made.has_value());
    prepared_view.rebuild(prepared, std::move(*made));

    // Bit for bit what is built from the same state by the same code; within the normal map
    // test's 1e-4 where one map was re-baked in part and the other in full (their mirrors'
    // height origins, and so their floats, differ then).
    const auto expect_same = [&](const char* when, bool fresh) {
        SCOPED_TRACE(when);
        expect_same_view({whole_renderer, whole_view, whole},
                         {prepared_renderer, prepared_view, prepared}, fresh ? 0.0f : 1e-4f);
        if (!fresh) return;
        // Refreshed twice a second after edits, on each view's own clock: compared when built.
        EXPECT_EQ(whole_view.mirror().graph().targets(), prepared_view.mirror().graph().targets());
        EXPECT_EQ(whole_view.contrast_low(), prepared_view.contrast_low());
        EXPECT_EQ(whole_view.contrast_high(), prepared_view.contrast_high());
    };
    EXPECT_FALSE(prepared_view.baking_normal_map()) << "the map comes baked from the worker";
    expect_same("after the rebuilds", true);
    ASSERT_FALSE(whole_view.mesh().constrained_edges().empty()) << "the rim is in the scene";

    // The same stamp on both, then a frame's update: still the same.
    const auto edit = [&](editor::Document& doc) {
        SculptContext c(domain);
        c.set_next_generation(context.peek_generation());
        stamp(doc.tin(), tool, {{0.6, 0.4}, 0.0, *doc.tin().height_at({0.6, 0.4}) - 0.01}, c);
    };
    edit(whole);
    edit(prepared);
    whole_view.update(whole, [] {});
    prepared_view.update(prepared, [] {});
    expect_same("after a stamp on both", false);

    // Prepared, then the terrain changes before the upload: the view shows the new terrain.
    std::optional<editor::PreparedView> behind;
    std::thread second([&] { behind.emplace(editor::TerrainView::prepare(prepared, *ctx_)); });
    second.join();
    const auto lift = [](editor::Document& doc) {
        const VertexId v = doc.tin().locate({0.3, 0.7}).corners[0];
        doc.tin().set_height(v, doc.tin().height(v) + 0.02);
    };
    lift(prepared);
    prepared_view.rebuild(prepared, std::move(*behind));
    lift(whole);
    whole_view.update(whole, [] {});
    expect_same("prepared, then lifted before the upload", false);
}

// A view is prepared on a worker (its mirror uploaded and its normal map baked there) while
// the UI thread goes on submitting work of its own to the same queue, as the editor draws and
// bakes while a scene opens. The validation layer's thread-safety checks (TearDown) see every
// submission; what the worker built is what the UI thread builds from the same scene.
TEST_F(Renderer, AViewPreparedWhileTheUIThreadSubmitsIsTheViewBuiltAfterwards) {
    const Rect domain{{0, 0}, {1, 1}};
    const std::filesystem::path scene =
        std::filesystem::temp_directory_path() / "sandtin-prepared-concurrently.sandtin";
    {
        Tin tin = Tin::random_points(domain, 20000, 3,
                                     [](Vec2 p) { return 0.1 + 0.05 * p.x - 0.03 * p.y; });
        save_session(scene, Session{tin.snapshot(), 0, "{}", {}});
    }
    editor::Document prepared = editor::Document::open(scene);
    editor::Document whole = editor::Document::open(scene);
    std::filesystem::remove(scene);

    // The UI thread's own work meanwhile: a small terrain lifted, synced and baked again.
    Tin busy = Tin::random_points(domain, 2000, 5, [](Vec2) { return 0.05; });
    gpu::TinMirror busy_mirror(*ctx_, busy);
    busy_mirror.sync();
    TerrainNormalMap busy_map(busy_mirror, domain, 256);
    std::atomic<bool> done{false};
    std::optional<editor::PreparedView> made;
    std::thread worker([&] {
        made.emplace(editor::TerrainView::prepare(prepared, *ctx_));
        done = true;
    });
    int rounds = 0;
    const VertexId lifted = busy.locate({0.5, 0.5}).corners[0];
    while (!done || rounds == 0) {
        busy.set_height(lifted, busy.height(lifted) + 1e-3);
        busy_mirror.sync();
        busy_map.bake_all();
        ++rounds;
    }
    worker.join();
    ASSERT_TRUE(made.has_value());

    TerrainRenderer prepared_renderer(*ctx_, pass_.get());
    TerrainRenderer whole_renderer(*ctx_, pass_.get());
    editor::TerrainView prepared_view(*ctx_, prepared_renderer);
    editor::TerrainView whole_view(*ctx_, whole_renderer);
    prepared_view.rebuild(prepared, std::move(*made));
    whole_view.rebuild(whole);
    EXPECT_FALSE(prepared_view.baking_normal_map()) << "the map comes baked from the worker";
    expect_same_view({whole_renderer, whole_view, whole},
                     {prepared_renderer, prepared_view, prepared}, 0.0f);
    EXPECT_EQ(whole_view.mirror().graph().targets(), prepared_view.mirror().graph().targets());
}

}  // namespace
}  // namespace sandtin::render
