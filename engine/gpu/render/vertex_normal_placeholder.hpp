#pragma once
// What terrain.frag samples while no baked normal map is ready (a terrain just installed, its
// map being baked a band of rows a frame, issue 42): a 1 x 1 RG16_SNORM texture whose texel has
// x = -1, which no baked texel of a height field has (its z would be 0). The shader then shades
// with the interpolated vertex normal, the same area-weighted smooth normal the baked map
// interpolates per texel, so the terrain looks the same before and after its map is ready.

#include <vulkan/vulkan.h>

#include "gpu/image.hpp"
#include "gpu/vk_handle.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

class VertexNormalPlaceholder {
  public:
    /// Creates the texture and fills its texel (waits for the GPU once).
    explicit VertexNormalPlaceholder(const gpu::VulkanContext& context);

    VkImageView view() const { return view_.get(); }
    VkSampler sampler() const { return sampler_.get(); }

  private:
    gpu::Image image_;
    gpu::UniqueImageView view_;
    gpu::UniqueSampler sampler_;
};

}  // namespace sandtin::render
