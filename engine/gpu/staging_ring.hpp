#pragma once
// Host-to-device uploads through a fixed-size, persistently mapped staging ring.
//
// upload() copies bytes into the ring and queues a copy region for the destination buffer;
// flush() records every queued region into one command buffer and submits it with a fence,
// without waiting. Ring space is reused only after the fence of the batch that used it has
// signalled, so the CPU runs ahead of the GPU by up to one ring of data. Uploads larger than
// the ring are split. Later submissions to the same queue see the data after a
// transfer -> shader barrier (submission order), which the compute recorders issue.
//
// Counts every byte it stages: total and since the last take_frame_bytes().

#include <vulkan/vulkan.h>

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/vk_handle.hpp"

namespace sandtin::gpu {

class VulkanContext;

class StagingRing {
  public:
    StagingRing(const VulkanContext& context, VkDeviceSize capacity);
    ~StagingRing();
    StagingRing(const StagingRing&) = delete;
    StagingRing& operator=(const StagingRing&) = delete;

    // Queues `bytes` from `data` for dst[dst_offset, dst_offset + bytes).
    void upload(VkBuffer dst, VkDeviceSize dst_offset, const void* data, VkDeviceSize bytes);
    // Submits the queued copies (no-op when none). Returns true when something was submitted.
    bool flush();
    // Waits for every submitted batch.
    void wait_idle();

    VkDeviceSize capacity() const { return capacity_; }
    uint64_t total_bytes() const { return total_bytes_; }
    // Bytes staged since the previous call.
    uint64_t take_frame_bytes();
    // Copy regions queued since the previous call (each costs the driver, and the validation
    // layer, work of its own).
    uint64_t take_frame_regions();
    uint64_t batches_submitted() const { return batches_; }

  private:
    struct InFlight {
        uint64_t end = 0;  // virtual ring position after this batch
        VkCommandBuffer cb = VK_NULL_HANDLE;
        UniqueFence fence;
    };
    // Waits for the oldest in-flight batch and releases its ring space.
    void retire_oldest();

    const VulkanContext& context_;
    VkDeviceSize capacity_;
    Buffer ring_;
    UniqueCommandPool pool_;
    std::deque<InFlight> in_flight_;
    std::vector<VkCommandBuffer> free_cbs_;
    std::vector<UniqueFence> free_fences_;
    std::map<VkBuffer, std::vector<VkBufferCopy>> pending_;
    uint64_t head_ = 0;  // virtual positions: physical = position % capacity
    uint64_t tail_ = 0;
    uint64_t total_bytes_ = 0;
    uint64_t frame_bytes_ = 0;
    uint64_t frame_regions_ = 0;
    uint64_t batches_ = 0;
};

}  // namespace sandtin::gpu
