#pragma once
// A VkBuffer with its own VkDeviceMemory. sandtin holds a few large buffers (one per TIN
// attribute), so one allocation per buffer is simple and well below maxMemoryAllocationCount.
//
// MemoryUse::Device     device-local; written by transfers or shaders only.
// MemoryUse::Upload     host-visible + coherent, persistently mapped; CPU writes, GPU reads.
// MemoryUse::Readback   host-visible (+ cached when available), persistently mapped; GPU
//                        writes, CPU reads after the fence (invalidated for non-coherent).

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpu/vk_handle.hpp"

namespace sandtin::gpu {

class VulkanContext;

enum class MemoryUse { Device, Upload, Readback };

class Buffer {
  public:
    Buffer() = default;
    // size in bytes (> 0); usage as for VkBufferCreateInfo.
    Buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
           MemoryUse use);

    VkBuffer get() const { return buffer_.get(); }
    VkDeviceSize size() const { return size_; }
    explicit operator bool() const { return static_cast<bool>(buffer_); }
    // Host pointer for Upload/Readback buffers, null for Device buffers.
    void* mapped() const { return mapped_; }
    // Makes device writes visible to the host (no-op on coherent memory).
    void invalidate(const VulkanContext& context) const;
    // Makes host writes visible to the device (no-op on coherent memory).
    void flush(const VulkanContext& context) const;

  private:
    UniqueBuffer buffer_;
    UniqueMemory memory_;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

// Buffer memory barrier for a whole buffer, for the common compute/transfer hazards.
void buffer_barrier(VkCommandBuffer cb, VkBuffer buffer, VkPipelineStageFlags src_stage,
                    VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                    VkAccessFlags dst_access);

// Global memory barrier: all writes of src_stage/src_access visible to dst.
void memory_barrier(VkCommandBuffer cb, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

// Compute and transfer writes -> compute and transfer reads and writes: between the dispatches
// and copies of one submission that read what the previous ones wrote (the water, sediment,
// moisture and surface-map kernels).
void compute_transfer_barrier(VkCommandBuffer cb);

// Transfer writes -> host reads: recorded after the last copy into a host-visible buffer that
// the host reads once the submission's fence has signalled. Waiting on the fence alone does not
// make device writes visible to the host (Vulkan spec, "Host Write Ordering Guarantees" and the
// fence's memory dependency, which excludes the host domain).
void host_read_barrier(VkCommandBuffer cb);

// Copies bytes [offset, offset + bytes) of a device buffer to the host and waits (after a
// barrier making earlier shader and transfer writes visible). For read-backs and tests.
std::vector<unsigned char> read_buffer(const VulkanContext& context, VkBuffer buffer,
                                       VkDeviceSize offset, VkDeviceSize bytes);
// The same for a buffer of 32-bit floats, from its start.
std::vector<float> read_buffer_floats(const VulkanContext& context, VkBuffer buffer,
                                      VkDeviceSize bytes);

}  // namespace sandtin::gpu
