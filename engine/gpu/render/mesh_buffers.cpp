#include "gpu/render/mesh_buffers.hpp"

#include <algorithm>
#include <cstring>

namespace sandtin::render {

void ensure_mesh_buffer(const gpu::VulkanContext& context, gpu::Buffer& buffer, VkDeviceSize bytes,
                        VkBufferUsageFlags usage) {
    if (buffer && buffer.size() >= bytes) return;
    buffer = gpu::Buffer(context, std::max<VkDeviceSize>(bytes + bytes / 2, 256), usage,
                         gpu::MemoryUse::Upload);
}

std::uint64_t write_constrained_edges(const gpu::VulkanContext& context, const TerrainMesh& mesh,
                                      MeshBuffers& out) {
    const auto& e = mesh.constrained_edges();
    out.constrained_count = static_cast<std::uint32_t>(e.size());
    if (e.empty()) return 0;
    const std::size_t bytes = e.size() * sizeof(std::uint32_t);
    ensure_mesh_buffer(context, out.constrained, bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    std::memcpy(out.constrained.mapped(), e.data(), bytes);
    out.constrained.flush(context);
    return bytes;
}

std::uint64_t write_whole_mesh(const gpu::VulkanContext& context, const TerrainMesh& mesh,
                               MeshBuffers& out) {
    const auto& v = mesh.vertices();
    const auto& idx = mesh.indices();
    const std::size_t vbytes = v.size() * sizeof(RenderVertex);
    const std::size_t ibytes = idx.size() * sizeof(std::uint32_t);
    ensure_mesh_buffer(context, out.vertices, vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    ensure_mesh_buffer(context, out.indices, ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (vbytes > 0) std::memcpy(out.vertices.mapped(), v.data(), vbytes);
    if (ibytes > 0) std::memcpy(out.indices.mapped(), idx.data(), ibytes);
    out.vertices.flush(context);
    out.indices.flush(context);
    out.index_count = static_cast<std::uint32_t>(idx.size());
    out.vertex_bytes = vbytes;
    return vbytes + ibytes + write_constrained_edges(context, mesh, out);
}

}  // namespace sandtin::render
