#pragma once
// The window's presentation target: swapchain, depth buffer, render pass and framebuffers,
// recreated on resize or when vsync is toggled, plus one frame in flight (a fence and two
// semaphores), which keeps CPU-side buffer rewrites simple and latency low.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "formats/png_image.hpp"
#include "gpu/buffer.hpp"
#include "gpu/image.hpp"
#include "gpu/vk_handle.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::editor {

using UniqueSwapchain = gpu::Unique<VkDevice, VkSwapchainKHR, &vkDestroySwapchainKHR>;
using gpu::UniqueFramebuffer;
using gpu::UniqueRenderPass;

class Swapchain {
  public:
    Swapchain(const gpu::VulkanContext& context, VkExtent2D extent, bool vsync);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    /// Rebuilds for a new framebuffer size or present mode (waits for the GPU first).
    void recreate(VkExtent2D extent, bool vsync);

    /// Waits for the previous frame, acquires an image and begins its command buffer and render
    /// pass (clear colour `clear`). Returns false when the swapchain is out of date (the caller
    /// recreates it and skips the frame).
    bool begin_frame(const float clear[3]);
    /// Ends the render pass, optionally copies the image for screenshot(), submits and
    /// presents. Returns false when the swapchain became out of date or suboptimal.
    bool end_frame(bool capture);
    /// Waits for the last submitted frame (before rewriting buffers it reads).
    void wait_idle() const;

    /// The image captured by the last end_frame(true), as 8-bit RGB.
    PngImage screenshot() const;

    VkCommandBuffer command_buffer() const { return command_buffer_; }
    VkRenderPass render_pass() const { return render_pass_.get(); }
    VkExtent2D extent() const { return extent_; }
    std::uint32_t image_count() const { return static_cast<std::uint32_t>(images_.size()); }
    std::uint64_t submissions() const { return submissions_; }

  private:
    void create(VkExtent2D extent, bool vsync);
    void destroy_targets();

    const gpu::VulkanContext& context_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    UniqueSwapchain swapchain_;
    std::vector<VkImage> images_;
    std::vector<gpu::UniqueImageView> views_;
    gpu::Image depth_image_;
    gpu::UniqueImageView depth_view_;
    UniqueRenderPass render_pass_;
    std::vector<UniqueFramebuffer> framebuffers_;
    gpu::UniqueCommandPool pool_;
    VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
    gpu::UniqueFence in_flight_;
    gpu::UniqueSemaphore image_ready_;
    gpu::UniqueSemaphore render_done_;
    std::uint32_t image_index_ = 0;
    std::uint64_t submissions_ = 0;
    gpu::Buffer readback_;
    VkExtent2D captured_{};
    bool bgr_ = false;
};

}  // namespace sandtin::editor
