#include "gpu/compute_kernel.hpp"

#include <optional>
#include <string>
#include <vector>

#include "gpu/dispatch_grid.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

ComputeKernel::ComputeKernel(const VulkanContext& context, std::string name,
                             std::span<const uint32_t> spirv, uint32_t buffers, uint32_t push_bytes)
    : device_(context.device()),
      name_(std::move(name)),
      buffers_(buffers),
      push_bytes_(push_bytes),
      max_groups_x_(context.dispatch_groups_x()),
      max_groups_y_(context.dispatch_groups_y()) {
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    if (buffers > limits.maxPerStageDescriptorStorageBuffers) {
        throw GpuError("kernel " + name_ + " needs " + std::to_string(buffers) +
                       " storage buffers per stage; the device allows " +
                       std::to_string(limits.maxPerStageDescriptorStorageBuffers));
    }
    if (push_bytes > limits.maxPushConstantsSize) {
        throw GpuError("kernel " + name_ + ": push constants exceed the device limit");
    }
    VkShaderModuleCreateInfo smci{};
    smci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    smci.codeSize = spirv.size_bytes();
    smci.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device_, &smci, nullptr, &module), "vkCreateShaderModule");
    module_ = UniqueShaderModule(device_, module);

    std::vector<VkDescriptorSetLayoutBinding> bindings(buffers);
    for (uint32_t i = 0; i < buffers; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo dslci{};
    dslci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    dslci.bindingCount = buffers;
    dslci.pBindings = bindings.data();
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(device_, &dslci, nullptr, &set_layout),
          "vkCreateDescriptorSetLayout");
    set_layout_ = UniqueDescriptorSetLayout(device_, set_layout);

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
    VkPipelineLayoutCreateInfo plci{};
    plci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &set_layout;
    plci.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    plci.pPushConstantRanges = push_bytes > 0 ? &range : nullptr;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device_, &plci, nullptr, &layout), "vkCreatePipelineLayout");
    layout_ = UniquePipelineLayout(device_, layout);

    VkComputePipelineCreateInfo cpci{};
    cpci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    cpci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpci.stage.module = module;
    cpci.stage.pName = "main";
    cpci.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &cpci, nullptr, &pipeline),
          "vkCreateComputePipelines");
    pipeline_ = UniquePipeline(device_, pipeline);

    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffers};
    VkDescriptorPoolCreateInfo dpci{};
    dpci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    dpci.maxSets = 1;
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device_, &dpci, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = UniqueDescriptorPool(device_, pool);

    VkDescriptorSetAllocateInfo dsai{};
    dsai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    dsai.descriptorPool = pool;
    dsai.descriptorSetCount = 1;
    dsai.pSetLayouts = &set_layout;
    check(vkAllocateDescriptorSets(device_, &dsai, &set_), "vkAllocateDescriptorSets");
}

void ComputeKernel::bind(std::span<const VkBuffer> buffers) {
    if (buffers.size() != buffers_) {
        throw GpuError("kernel " + name_ + ": bind() got " + std::to_string(buffers.size()) +
                       " buffers, expected " + std::to_string(buffers_));
    }
    std::vector<VkDescriptorBufferInfo> infos(buffers_);
    std::vector<VkWriteDescriptorSet> writes(buffers_);
    for (uint32_t i = 0; i < buffers_; ++i) {
        if (buffers[i] == VK_NULL_HANDLE) {
            throw GpuError("kernel " + name_ + ": binding " + std::to_string(i) + " is null");
        }
        infos[i] = {buffers[i], 0, VK_WHOLE_SIZE};
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = set_;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(device_, buffers_, writes.data(), 0, nullptr);
    bound_ = true;
}

void ComputeKernel::prepare(VkCommandBuffer cb, const void* push) const {
    if (!bound_) throw GpuError("kernel " + name_ + " dispatched before bind()");
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0,
                            nullptr);
    if (push_bytes_ > 0) {
        if (push == nullptr) throw GpuError("kernel " + name_ + " needs push constants");
        vkCmdPushConstants(cb, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
    }
}

void ComputeKernel::dispatch(VkCommandBuffer cb, uint32_t threads, const void* push) const {
    if (threads == 0) return;
    const uint32_t groups = (threads - 1) / kLocalSize + 1;  // no overflow near UINT32_MAX
    const std::optional<DispatchGrid> grid = dispatch_grid(groups, max_groups_x_, max_groups_y_);
    if (!grid) {
        throw GpuError("kernel " + name_ + ": " + std::to_string(threads) +
                       " threads exceed the device's workgroup grid");
    }
    prepare(cb, push);
    vkCmdDispatch(cb, grid->x, grid->y, 1);
}

void ComputeKernel::dispatch_indirect(VkCommandBuffer cb, VkBuffer args, VkDeviceSize offset,
                                      const void* push) const {
    prepare(cb, push);
    vkCmdDispatchIndirect(cb, args, offset);
}

}  // namespace sandtin::gpu
