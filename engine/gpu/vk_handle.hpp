#pragma once
// Move-only owners for Vulkan handles: the one place where vkDestroy* is called.
// A handle created from a VkDevice is destroyed with that device; instance-level handles
// (surface) with their instance. Destruction order is the owner's member order, so owners
// declare the device/instance before the handles that depend on them.

#include <vulkan/vulkan.h>

#include <utility>

namespace sandtin::gpu {

// Owns a handle created from `Parent` (VkDevice or VkInstance) and destroyed by `Destroy`.
template <typename Parent, typename Handle,
          void (*Destroy)(Parent, Handle, const VkAllocationCallbacks*)>
class Unique {
  public:
    Unique() = default;
    Unique(Parent parent, Handle handle) : parent_(parent), handle_(handle) {}
    ~Unique() { reset(); }

    Unique(const Unique&) = delete;
    Unique& operator=(const Unique&) = delete;
    Unique(Unique&& other) noexcept
        : parent_(other.parent_), handle_(std::exchange(other.handle_, Handle{})) {}
    Unique& operator=(Unique&& other) noexcept {
        if (this != &other) {
            reset();
            parent_ = other.parent_;
            handle_ = std::exchange(other.handle_, Handle{});
        }
        return *this;
    }

    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != Handle{}; }

    void reset() {
        if (handle_ != Handle{}) Destroy(parent_, std::exchange(handle_, Handle{}), nullptr);
    }

  private:
    Parent parent_{};
    Handle handle_{};
};

// Owns a root handle (VkInstance, VkDevice) destroyed without a parent.
template <typename Handle, void (*Destroy)(Handle, const VkAllocationCallbacks*)>
class UniqueRoot {
  public:
    UniqueRoot() = default;
    explicit UniqueRoot(Handle handle) : handle_(handle) {}
    ~UniqueRoot() { reset(); }

    UniqueRoot(const UniqueRoot&) = delete;
    UniqueRoot& operator=(const UniqueRoot&) = delete;
    UniqueRoot(UniqueRoot&& other) noexcept : handle_(std::exchange(other.handle_, Handle{})) {}
    UniqueRoot& operator=(UniqueRoot&& other) noexcept {
        if (this != &other) {
            reset();
            handle_ = std::exchange(other.handle_, Handle{});
        }
        return *this;
    }

    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != Handle{}; }

    void reset() {
        if (handle_ != Handle{}) Destroy(std::exchange(handle_, Handle{}), nullptr);
    }

  private:
    Handle handle_{};
};

using UniqueInstance = UniqueRoot<VkInstance, &vkDestroyInstance>;
using UniqueDevice = UniqueRoot<VkDevice, &vkDestroyDevice>;
using UniqueSurface = Unique<VkInstance, VkSurfaceKHR, &vkDestroySurfaceKHR>;

using UniqueBuffer = Unique<VkDevice, VkBuffer, &vkDestroyBuffer>;
using UniqueMemory = Unique<VkDevice, VkDeviceMemory, &vkFreeMemory>;
using UniqueImage = Unique<VkDevice, VkImage, &vkDestroyImage>;
using UniqueImageView = Unique<VkDevice, VkImageView, &vkDestroyImageView>;
using UniqueCommandPool = Unique<VkDevice, VkCommandPool, &vkDestroyCommandPool>;
using UniqueFence = Unique<VkDevice, VkFence, &vkDestroyFence>;
using UniqueSemaphore = Unique<VkDevice, VkSemaphore, &vkDestroySemaphore>;
using UniqueShaderModule = Unique<VkDevice, VkShaderModule, &vkDestroyShaderModule>;
using UniquePipeline = Unique<VkDevice, VkPipeline, &vkDestroyPipeline>;
using UniquePipelineLayout = Unique<VkDevice, VkPipelineLayout, &vkDestroyPipelineLayout>;
using UniqueDescriptorSetLayout =
    Unique<VkDevice, VkDescriptorSetLayout, &vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = Unique<VkDevice, VkDescriptorPool, &vkDestroyDescriptorPool>;
using UniqueQueryPool = Unique<VkDevice, VkQueryPool, &vkDestroyQueryPool>;
using UniqueSampler = Unique<VkDevice, VkSampler, &vkDestroySampler>;
using UniqueRenderPass = Unique<VkDevice, VkRenderPass, &vkDestroyRenderPass>;
using UniqueFramebuffer = Unique<VkDevice, VkFramebuffer, &vkDestroyFramebuffer>;

}  // namespace sandtin::gpu
