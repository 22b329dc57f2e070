#pragma once
// Draws the terrain (one pipeline: lit, detail-normal, material albedo, contrast curve,
// overlays and the tool cursor, all in terrain.frag) inside a render pass the caller owns, so
// it serves a swapchain and an offscreen target alike.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "gpu/buffer.hpp"
#include "gpu/render/terrain_vertices.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

/// Push constants of terrain.vert / terrain.frag (std430 layout, 128 bytes).
struct TerrainPush {
    float view_projection[16];  ///< column-major
    float light_dir[4];         ///< xyz towards the light; w contrast strength [0, 1]
    float cursor[4];            ///< xy centre (m, domain-centre relative), z radius (m), w shown
    float overlays[4];          ///< wireframe, active, sand thickness, slope vs repose (0/1)
    float contrast[4];          ///< x low, y high height (m) of the stretch
};
static_assert(sizeof(TerrainPush) == 128);

class TerrainRenderer {
  public:
    /// The render pass must have one colour attachment and a depth attachment.
    TerrainRenderer(const gpu::VulkanContext& context, VkRenderPass render_pass);

    /// Replaces the vertex data. The previous buffer must no longer be in use by the GPU.
    void upload(std::span<const TerrainVertex> vertices);
    /// Records the draw (viewport and scissor are dynamic).
    void draw(VkCommandBuffer cb, const TerrainPush& push, VkExtent2D extent) const;

    std::size_t vertex_count() const { return vertex_count_; }
    std::uint64_t bytes_uploaded() const { return bytes_uploaded_; }

  private:
    const gpu::VulkanContext& context_;
    gpu::UniquePipelineLayout layout_;
    gpu::UniquePipeline pipeline_;
    gpu::Buffer vertices_;
    std::size_t vertex_count_ = 0;
    std::uint64_t bytes_uploaded_ = 0;
};

}  // namespace sandtin::render
