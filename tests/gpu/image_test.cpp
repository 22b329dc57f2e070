// gpu::Image, create_image_view and image_barrier: what the normal map and the editor's depth
// buffer are built from. Every test runs under the validation layer (GpuTest fails on any
// message), which checks the layouts the barriers claim.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/image.hpp"
#include "gpu_fixture.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

TEST_F(GpuTest, EmptyImageExtentIsAClearErrorNamingTheImage) {
    try {
        Image(ctx(), {VK_FORMAT_R32_SFLOAT, {0, 4}, VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test map"});
        FAIL() << "an image with no texels was created";
    } catch (const GpuError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("test map"), std::string::npos) << what;
        EXPECT_NE(what.find("extent"), std::string::npos) << what;
    }
}

// Clear a 5 x 3 image through UNDEFINED -> TRANSFER_DST -> TRANSFER_SRC and copy it out: every
// texel must hold the clear value (the oracle), and a barrier with a wrong layout would be a
// validation message.
TEST_F(GpuTest, ClearedImageReadsBackThroughItsBarriers) {
    const VkExtent2D extent{5, 3};
    const Image image(
        ctx(), {VK_FORMAT_R32_SFLOAT, extent,
                VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "cleared"});
    ASSERT_TRUE(image);
    const VkDeviceSize bytes = VkDeviceSize{extent.width} * extent.height * sizeof(float);
    Buffer down(ctx(), bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    ctx().submit_and_wait([&](VkCommandBuffer cb) {
        image_barrier(cb, image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                      0, VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkClearColorValue value{};
        value.float32[0] = 2.5f;
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cb, image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1,
                             &all);
        image_barrier(cb, image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy c{};
        c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        c.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyImageToBuffer(cb, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, down.get(), 1,
                               &c);
        buffer_barrier(cb, down.get(), VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    down.invalidate(ctx());
    const auto* texels = static_cast<const float*>(down.mapped());
    const std::vector<float> back(texels, texels + extent.width * extent.height);
    EXPECT_EQ(back, std::vector<float>(15, 2.5f));
}

// The editor re-creates its depth buffer on resize by assigning a new Image over the old one,
// with a depth view over each: the old image must go before its memory, without a message.
TEST_F(GpuTest, DepthImageReassignedWithItsViewStaysValidationClean) {
    const ImageSpec small{
        VK_FORMAT_D32_SFLOAT, {8, 8}, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth"};
    Image depth(ctx(), small);
    UniqueImageView view = create_image_view(ctx().device(), depth.get(), VK_FORMAT_D32_SFLOAT,
                                             VK_IMAGE_ASPECT_DEPTH_BIT, "depth");
    EXPECT_TRUE(view);
    view.reset();
    ImageSpec large = small;
    large.extent = {32, 16};
    depth = Image(ctx(), large);
    view = create_image_view(ctx().device(), depth.get(), VK_FORMAT_D32_SFLOAT,
                             VK_IMAGE_ASPECT_DEPTH_BIT, "depth");
    EXPECT_TRUE(view);
    Image moved = std::move(depth);
    EXPECT_TRUE(moved);
    EXPECT_FALSE(depth);  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
    view.reset();
}

}  // namespace
}  // namespace sandtin::gpu
