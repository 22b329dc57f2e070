#pragma once
// 2D device images: the image with its own memory, views over a whole image, and layout
// barriers. The one place the renderer's textures and the editor's depth buffer are made.

#include "gpu/vk_handle.hpp"

#include <vulkan/vulkan.h>

#include <utility>

namespace sandtin::gpu {

class VulkanContext;

/// What a 2D image is: one mip level, one layer, optimal tiling, one queue family.
struct ImageSpec {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};  ///< texels; both sides > 0
    VkImageUsageFlags usage = 0;
    const char* what = "image";  ///< named in error messages
};

/// A 2D image bound to device-local memory of its own (host-visible memory is accepted when
/// the device has nothing else, as lavapipe). Move-only; destroyed before its memory.
class Image {
  public:
    Image() = default;
    /// Throws GpuError naming `spec.what` when the device refuses the image or its memory.
    Image(const VulkanContext& context, const ImageSpec& spec);
    Image(Image&&) noexcept = default;
    /// Destroys the image it held before that image's memory.
    Image& operator=(Image&& other) noexcept {
        if (this != &other) {
            image_.reset();
            memory_ = std::move(other.memory_);
            image_ = std::move(other.image_);
        }
        return *this;
    }

    VkImage get() const { return image_.get(); }
    explicit operator bool() const { return static_cast<bool>(image_); }

  private:
    UniqueMemory memory_;  // declared first: destroyed after the image it backs
    UniqueImage image_;
};

/// A 2D view of all of `image` (level 0, layer 0) through `aspect` (colour or depth).
UniqueImageView create_image_view(VkDevice device, VkImage image, VkFormat format,
                                  VkImageAspectFlags aspect, const char* what);

/// Layout transition of all of a 2D image (level 0, layer 0), with the hazards it orders.
void image_barrier(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspect,
                   VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkImageLayout old_layout, VkPipelineStageFlags dst_stage,
                   VkAccessFlags dst_access, VkImageLayout new_layout);

}  // namespace sandtin::gpu
