#include "gpu/render/vertex_normal_placeholder.hpp"

#include "gpu/gpu_error.hpp"

namespace sandtin::render {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_R16G16_SNORM;  // the baked map's format

}  // namespace

VertexNormalPlaceholder::VertexNormalPlaceholder(const gpu::VulkanContext& context) {
    const VkDevice device = context.device();
    image_ = gpu::Image(context, {kFormat,
                                  {1, 1},
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                  "vertex-normal placeholder map"});
    view_ = gpu::create_image_view(device, image_.get(), kFormat, VK_IMAGE_ASPECT_COLOR_BIT,
                                   "vertex-normal placeholder map");
    VkSamplerCreateInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;  // the texel exactly, x = -1
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler sampler = VK_NULL_HANDLE;
    gpu::check(vkCreateSampler(device, &si, nullptr, &sampler),
               "vkCreateSampler (vertex-normal placeholder map)");
    sampler_ = gpu::UniqueSampler(device, sampler);
    const VkImage image = image_.get();
    context.submit_and_wait([&](VkCommandBuffer cb) {
        gpu::image_barrier(cb, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                           0, VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkClearColorValue value{};
        value.float32[0] = -1.0f;  // SNORM: -32767, decoded as exactly -1
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cb, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
        gpu::image_barrier(cb, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
}

}  // namespace sandtin::render
