#include "gpu/staging_ring.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

StagingRing::StagingRing(const VulkanContext& context, VkDeviceSize capacity)
    : context_(context),
      capacity_(capacity),
      ring_(context, capacity, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload) {
    VkCommandPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(context.device(), &pci, nullptr, &pool), "vkCreateCommandPool");
    pool_ = UniqueCommandPool(context.device(), pool);
}

StagingRing::~StagingRing() {
    // Command buffers die with the pool; the fences must not be in use.
    while (!in_flight_.empty()) {
        VkFence f = in_flight_.front().fence.get();
        vkWaitForFences(context_.device(), 1, &f, VK_TRUE, UINT64_MAX);
        in_flight_.pop_front();
    }
}

void StagingRing::retire_oldest() {
    InFlight& b = in_flight_.front();
    VkFence f = b.fence.get();
    check(vkWaitForFences(context_.device(), 1, &f, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(context_.device(), 1, &f), "vkResetFences");
    tail_ = b.end;
    free_cbs_.push_back(b.cb);
    free_fences_.push_back(std::move(b.fence));
    in_flight_.pop_front();
}

void StagingRing::upload(VkBuffer dst, VkDeviceSize dst_offset, const void* data,
                         VkDeviceSize bytes) {
    const auto* src = static_cast<const unsigned char*>(data);
    total_bytes_ += bytes;
    frame_bytes_ += bytes;
    while (bytes > 0) {
        if (in_flight_.empty() && pending_.empty()) {
            // The whole ring is free: start again at its physical beginning, where the most
            // contiguous room is. (Kept where it was, an unaligned head near the end of the ring
            // left the ring 15 bytes short of free, with a small contiguous piece before the
            // wrap and nothing in flight to reclaim: the branch below threw.)
            head_ = tail_ = (head_ + capacity_ - 1) / capacity_ * capacity_;
        }
        // Regions start 16-byte aligned (copy offsets need 4; 16 keeps vec4 data aligned).
        head_ = (head_ + 15) & ~uint64_t{15};
        uint64_t phys = head_ % capacity_;
        uint64_t contiguous = capacity_ - phys;
        if (contiguous < 16) {  // too close to the end: wrap
            head_ += contiguous;
            continue;
        }
        const uint64_t used = head_ - tail_;
        const uint64_t free_space = used >= capacity_ ? 0 : capacity_ - used;
        const uint64_t chunk = std::min<uint64_t>({bytes, contiguous, free_space});
        if (chunk == 0 || (chunk < bytes && chunk < 4096 && free_space < capacity_)) {
            // Not enough room: submit what is queued and reclaim the oldest batch.
            flush();
            if (in_flight_.empty()) {
                throw GpuError("StagingRing: no space although nothing is in flight");
            }
            retire_oldest();
            continue;
        }
        std::memcpy(static_cast<unsigned char*>(ring_.mapped()) + phys, src, chunk);
        pending_[dst].push_back(VkBufferCopy{phys, dst_offset, chunk});
        ++frame_regions_;
        head_ += chunk;
        src += chunk;
        dst_offset += chunk;
        bytes -= chunk;
    }
}

bool StagingRing::flush() {
    if (pending_.empty()) return false;
    ring_.flush(context_);
    VkCommandBuffer cb = VK_NULL_HANDLE;
    if (!free_cbs_.empty()) {
        cb = free_cbs_.back();
        free_cbs_.pop_back();
        check(vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
    } else {
        VkCommandBufferAllocateInfo ai{};
        ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
        ai.commandPool = pool_.get();
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        check(vkAllocateCommandBuffers(context_.device(), &ai, &cb), "vkAllocateCommandBuffers");
    }
    UniqueFence fence;
    if (!free_fences_.empty()) {
        fence = std::move(free_fences_.back());
        free_fences_.pop_back();
    } else {
        VkFenceCreateInfo fci{};
        fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
        VkFence f = VK_NULL_HANDLE;
        check(vkCreateFence(context_.device(), &fci, nullptr, &f), "vkCreateFence");
        fence = UniqueFence(context_.device(), f);
    }
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    // Earlier shader work may still read these buffers (write-after-read) or have written them.
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    for (const auto& [dst, regions] : pending_) {
        vkCmdCopyBuffer(cb, ring_.get(), dst, static_cast<uint32_t>(regions.size()),
                        regions.data());
    }
    check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
    pending_.clear();

    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    {
        std::lock_guard lock(context_.queue_mutex());
        check(vkQueueSubmit(context_.queue(), 1, &si, fence.get()), "vkQueueSubmit");
    }
    in_flight_.push_back(InFlight{head_, cb, std::move(fence)});
    ++batches_;
    return true;
}

void StagingRing::wait_idle() {
    while (!in_flight_.empty())
        retire_oldest();
}

uint64_t StagingRing::take_frame_bytes() {
    return std::exchange(frame_bytes_, 0);
}

uint64_t StagingRing::take_frame_regions() {
    return std::exchange(frame_regions_, 0);
}

}  // namespace sandtin::gpu
