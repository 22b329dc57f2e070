#pragma once
// One compute shader with its pipeline, its descriptor set of storage buffers (bindings
// 0..n-1, set 0) and a push-constant block. The set is rewritten with bind() whenever a
// buffer is reallocated; callers only bind while no submitted work uses the set (sandtin
// waits for each submission before recording the next).

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "gpu/vk_handle.hpp"

namespace sandtin::gpu {

class VulkanContext;

class ComputeKernel {
  public:
    // `spirv` is the embedded SPIR-V; `buffers` the number of storage-buffer bindings;
    // `push_bytes` the size of the push-constant block (0 for none).
    ComputeKernel(const VulkanContext& context, std::string name, std::span<const uint32_t> spirv,
                  uint32_t buffers, uint32_t push_bytes);

    const std::string& name() const { return name_; }
    // Points binding i at buffers[i] (whole buffer). buffers.size() must equal the binding count.
    void bind(std::span<const VkBuffer> buffers);

    // Binds pipeline + set and pushes `push` (push_bytes long) on `cb`.
    void prepare(VkCommandBuffer cb, const void* push) const;
    // prepare() and vkCmdDispatch for `threads` invocations (workgroups of kLocalSize, in rows
    // when one row would pass the device's limit: dispatch_grid.hpp). Throws GpuError when
    // even the 2-D grid is too small.
    void dispatch(VkCommandBuffer cb, uint32_t threads, const void* push = nullptr) const;
    // prepare() and vkCmdDispatchIndirect from `args` at `offset`.
    void dispatch_indirect(VkCommandBuffer cb, VkBuffer args, VkDeviceSize offset,
                           const void* push = nullptr) const;

    static constexpr uint32_t kLocalSize = 64;  // must match local_size_x in the shaders

  private:
    VkDevice device_;
    std::string name_;
    uint32_t buffers_;
    uint32_t push_bytes_;
    uint32_t max_groups_x_;
    uint32_t max_groups_y_;
    UniqueShaderModule module_;
    UniqueDescriptorSetLayout set_layout_;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
    UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    bool bound_ = false;
};

}  // namespace sandtin::gpu
