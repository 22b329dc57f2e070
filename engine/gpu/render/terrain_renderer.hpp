#pragma once
// Draws the terrain inside a render pass the caller owns (so it serves a swapchain and an
// offscreen target alike): one indexed draw of the lit surface (baked normal map sampled by
// world xy, detail normal, material albedo, contrast curve, overlays and tool cursor, all in
// terrain.frag); then, where water stands, its surface, blended over it (water.frag, on the
// triangles with a wet corner only: nothing on a dry terrain); then, only when the wireframe
// overlay is on, a line pass over every edge (the triangles' outlines) and one over the
// constrained edges. Buffers mirror TerrainMesh and receive only the ranges an update names.

#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "gpu/buffer.hpp"
#include "gpu/render/mesh_buffers.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/render/vertex_normal_placeholder.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

/// Push constants of terrain.vert / terrain.frag (std430 layout, 128 bytes).
struct TerrainPush {
    float view_projection[16];  ///< column-major
    float light_dir[4];         ///< xyz towards the light; w contrast strength [0, 1]
    float cursor[4];            ///< xy centre (m, domain-centre relative), z radius (m), w shown
    /// x: bits, 1 the wireframe, 2 the water-depth, 4 the water-speed and 8 the sediment
    /// overlay (the last three drawn on the water's surface; 128 bytes hold no more);
    /// y active, z sand thickness, w slope vs repose (0/1)
    float overlays[4];
    /// x low, y high height (m) of the stretch; z = 1 / domain width, w = 1 / domain height
    /// (1/m): the normal map's texture coordinates of a centre-relative position
    float contrast[4];
};
static_assert(sizeof(TerrainPush) == 128);
inline constexpr float kOverlayWireframe = 1.0f;
inline constexpr float kOverlayWaterDepth = 2.0f;
inline constexpr float kOverlayWaterSpeed = 4.0f;
inline constexpr float kOverlaySediment = 8.0f;
/// Whether overlays[0] has `bit` (kOverlayWireframe, kOverlayWaterDepth, kOverlayWaterSpeed,
/// kOverlaySediment).
inline bool has_overlay_bit(float bits, float bit) {
    return (static_cast<int>(bits + 0.5f) & static_cast<int>(bit)) != 0;
}

class TerrainRenderer {
  public:
    /// The render pass must have one colour attachment and a depth attachment.
    TerrainRenderer(const gpu::VulkanContext& context, VkRenderPass render_pass);

    /// Copies the ranges `update` names from `mesh` (everything when it says resized). The GPU
    /// must not be reading the buffers (the caller waits for the previous frame).
    void upload(const TerrainMesh& mesh, const MeshUpdate& update);
    /// Draws from `buffers` from now on: a whole mesh written elsewhere (write_whole_mesh, on
    /// a worker thread that opened a scene), in place of whatever was drawn before. `mesh` is
    /// what they hold. The GPU must not be drawing.
    void adopt(MeshBuffers buffers, const TerrainMesh& mesh);
    /// The baked normal map terrain.frag samples (TerrainNormalMap). Set again when the map is
    /// replaced; the GPU must not be drawing.
    void set_normal_map(VkImageView view, VkSampler sampler);
    /// No baked map (as after construction): the terrain is shaded with its interpolated vertex
    /// normals (vertex_normal_placeholder.hpp) until set_normal_map(). Call before the map in
    /// use is destroyed; the GPU must not be drawing.
    void use_vertex_normals();
    /// Records the draws (viewport and scissor are dynamic). With the wireframe overlay on,
    /// the edge list is rebuilt from `mesh` when its triangles changed since the last call.
    /// `eye` is the camera's position (metres, domain-centre relative): the water's surface
    /// reflects more of the sky the more obliquely it is seen.
    void draw(VkCommandBuffer cb, const TerrainPush& push, const float eye[3], VkExtent2D extent,
              const TerrainMesh& mesh);

    /// Records a closed outline (metres, domain-centre relative, already at the terrain's
    /// height) as lines of `colour` (RGBA): the tool cursor's footprint. Call once per frame
    /// after draw(); it reuses one small buffer, which the previous frame no longer reads.
    void draw_outline(VkCommandBuffer cb, const float view_projection[16],
                      std::span<const std::array<float, 3>> loop, const float colour[4]);

    std::uint64_t bytes_uploaded() const { return bytes_uploaded_; }
    /// Triangles the last draw() drew the water's surface on (0: no water pass recorded).
    std::uint32_t water_triangles_drawn() const { return water_drawn_; }

    /// Forgets the mesh: its buffers go, and the next upload (which must be a rebuild's)
    /// allocates them again, so nothing of a replaced terrain stays in memory the renderer
    /// draws from. Draws nothing until then. The GPU must not be drawing.
    void drop_mesh();
    /// What the GPU draws from: the vertex and index buffers' bytes for the mesh last
    /// uploaded (its vertices() and indices() sizes). For tests, which compare them with the
    /// mesh.
    std::span<const std::byte> drawn_vertex_bytes() const;
    std::span<const std::byte> drawn_index_bytes() const;

  private:
    void ensure(gpu::Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage);
    void draw_water(VkCommandBuffer cb, const TerrainPush& push, const float eye[3],
                    const TerrainMesh& mesh);

    const gpu::VulkanContext& context_;
    gpu::UniqueDescriptorSetLayout set_layout_;
    gpu::UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  ///< freed with pool_
    VertexNormalPlaceholder placeholder_;
    gpu::UniquePipelineLayout terrain_layout_;
    gpu::UniquePipeline terrain_pipeline_;
    gpu::UniquePipelineLayout lines_layout_;
    gpu::UniquePipeline lines_pipeline_;
    /// The wireframe drawn from the triangles with line polygons (null without the device's
    /// fillModeNonSolid: then an edge list, wire_, is built on the CPU).
    gpu::UniquePipeline wire_pipeline_;
    gpu::UniquePipelineLayout water_layout_;
    gpu::UniquePipeline water_pipeline_;
    MeshBuffers mesh_;
    gpu::Buffer wire_;
    gpu::Buffer outline_;
    gpu::Buffer water_;  ///< TerrainMesh::water_indices(), as of water_version_
    std::uint32_t water_count_ = 0;
    std::uint64_t water_version_ = ~std::uint64_t{0};
    std::uint32_t water_drawn_ = 0;
    std::uint32_t wire_count_ = 0;
    bool wire_stale_ = true;
    std::uint64_t bytes_uploaded_ = 0;
};

}  // namespace sandtin::render
