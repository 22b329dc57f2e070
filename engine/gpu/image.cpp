#include "gpu/image.hpp"

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

#include <string>

namespace sandtin::gpu {

Image::Image(const VulkanContext& context, const ImageSpec& spec) {
    const VkDevice device = context.device();
    const std::string what = spec.what;
    if (spec.extent.width == 0 || spec.extent.height == 0)
        throw GpuError("cannot create " + what + ": its extent is empty");
    VkImageCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = spec.format;
    ii.extent = {spec.extent.width, spec.extent.height, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = spec.usage;
    ii.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    check(vkCreateImage(device, &ii, nullptr, &image), ("vkCreateImage (" + what + ")").c_str());
    image_ = UniqueImage(device, image);

    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        context.memory_type(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &ai, nullptr, &memory),
          ("vkAllocateMemory (" + what + ")").c_str());
    memory_ = UniqueMemory(device, memory);
    check(vkBindImageMemory(device, image, memory, 0),
          ("vkBindImageMemory (" + what + ")").c_str());
}

UniqueImageView create_image_view(VkDevice device, VkImage image, VkFormat format,
                                  VkImageAspectFlags aspect, const char* what) {
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(device, &vi, nullptr, &view),
          ("vkCreateImageView (" + std::string(what) + ")").c_str());
    return UniqueImageView(device, view);
}

void image_barrier(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspect,
                   VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkImageLayout old_layout, VkPipelineStageFlags dst_stage,
                   VkAccessFlags dst_access, VkImageLayout new_layout) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = old_layout;
    b.newLayout = new_layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace sandtin::gpu
