#pragma once
// The render mesh's GPU buffers: its vertices, its triangles' indices and its constrained
// edges, in host-visible, persistently mapped memory that the renderer draws from and then
// patches range by range as the terrain changes (TerrainRenderer::upload).
//
// Written whole by write_whole_mesh(), which touches no queue: a worker thread can fill the
// buffers of a scene it opened while the UI thread goes on drawing the old one, and the
// renderer then adopts them (TerrainRenderer::adopt). At 10^6 vertices the whole write took
// 305 ms of the UI thread's install frame on lavapipe.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

#include "gpu/buffer.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::render {

struct MeshBuffers {
    gpu::Buffer vertices;     ///< RenderVertex per mesh vertex
    gpu::Buffer indices;      ///< three per triangle slot
    gpu::Buffer constrained;  ///< line-list indices of the constrained edges (may be empty)
    std::uint32_t index_count = 0;
    std::uint32_t constrained_count = 0;
    std::size_t vertex_bytes = 0;  ///< of the mesh last written
};

/// Grows `buffer` to hold `bytes` (half again as headroom, so a terrain that gains vertices
/// does not reallocate every edit); its contents are lost when it grows. Any thread.
void ensure_mesh_buffer(const gpu::VulkanContext& context, gpu::Buffer& buffer, VkDeviceSize bytes,
                        VkBufferUsageFlags usage);

/// Copies all of `mesh` into `out`, growing its buffers as needed. Returns the bytes written.
/// Any thread: it allocates and maps memory but submits nothing; the GPU must not be reading
/// `out` meanwhile.
std::uint64_t write_whole_mesh(const gpu::VulkanContext& context, const TerrainMesh& mesh,
                               MeshBuffers& out);

/// Copies the constrained edges of `mesh` into `out`. Returns the bytes written.
std::uint64_t write_constrained_edges(const gpu::VulkanContext& context, const TerrainMesh& mesh,
                                      MeshBuffers& out);

}  // namespace sandtin::render
