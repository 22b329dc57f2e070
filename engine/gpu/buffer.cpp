#include "gpu/buffer.hpp"

#include <cstring>

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

Buffer::Buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage,
               MemoryUse use)
    : size_(size) {
    if (size == 0) throw GpuError("Buffer: size must be positive");
    VkDevice device = context.device();
    VkBufferCreateInfo bci{};
    bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bci.size = size;
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(device, &bci, nullptr, &buffer), "vkCreateBuffer");
    buffer_ = UniqueBuffer(device, buffer);

    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, buffer, &req);
    VkMemoryPropertyFlags required = 0;
    VkMemoryPropertyFlags preferred = 0;
    switch (use) {
        case MemoryUse::Device:
            required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryUse::Upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUse::Readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    const uint32_t type = context.memory_type(req.memoryTypeBits, required, preferred);
    coherent_ = (context.memory_properties().memoryTypes[type].propertyFlags &
                 VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;

    VkMemoryAllocateInfo mai{};
    mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &mai, nullptr, &memory), "vkAllocateMemory");
    memory_ = UniqueMemory(device, memory);
    check(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
    if (use != MemoryUse::Device) {
        // Unmapped implicitly by vkFreeMemory.
        check(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    }
}

void Buffer::invalidate(const VulkanContext& context) const {
    if (coherent_ || mapped_ == nullptr) return;
    VkMappedMemoryRange r{};
    r.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
    r.memory = memory_.get();
    r.size = VK_WHOLE_SIZE;
    check(vkInvalidateMappedMemoryRanges(context.device(), 1, &r),
          "vkInvalidateMappedMemoryRanges");
}

void Buffer::flush(const VulkanContext& context) const {
    if (coherent_ || mapped_ == nullptr) return;
    VkMappedMemoryRange r{};
    r.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
    r.memory = memory_.get();
    r.size = VK_WHOLE_SIZE;
    check(vkFlushMappedMemoryRanges(context.device(), 1, &r), "vkFlushMappedMemoryRanges");
}

void buffer_barrier(VkCommandBuffer cb, VkBuffer buffer, VkPipelineStageFlags src_stage,
                    VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                    VkAccessFlags dst_access) {
    VkBufferMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 1, &b, 0, nullptr);
}

void memory_barrier(VkCommandBuffer cb, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void compute_transfer_barrier(VkCommandBuffer cb) {
    memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                       VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

void host_read_barrier(VkCommandBuffer cb) {
    memory_barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

std::vector<unsigned char> read_buffer(const VulkanContext& context, VkBuffer buffer,
                                       VkDeviceSize offset, VkDeviceSize bytes) {
    std::vector<unsigned char> out(bytes);
    if (bytes == 0) return out;
    Buffer host(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    context.submit_and_wait([&](VkCommandBuffer cb) {
        memory_barrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy c{offset, 0, bytes};
        vkCmdCopyBuffer(cb, buffer, host.get(), 1, &c);
        host_read_barrier(cb);
    });
    host.invalidate(context);
    std::memcpy(out.data(), host.mapped(), bytes);
    return out;
}

std::vector<float> read_buffer_floats(const VulkanContext& context, VkBuffer buffer,
                                      VkDeviceSize bytes) {
    const std::vector<unsigned char> raw = read_buffer(context, buffer, 0, bytes);
    std::vector<float> out(raw.size() / sizeof(float));
    std::memcpy(out.data(), raw.data(), out.size() * sizeof(float));
    return out;
}

}  // namespace sandtin::gpu
