#include "swapchain.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <mutex>

#include "gpu/gpu_error.hpp"
#include "gpu/image.hpp"

namespace sandtin::editor {

using gpu::check;

Swapchain::Swapchain(const gpu::VulkanContext& context, VkExtent2D extent, bool vsync)
    : context_(context) {
    const VkDevice device = context.device();
    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    pool_ = gpu::UniqueCommandPool(device, pool);
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(device, &alloc, &command_buffer_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(device, &fence_info, nullptr, &fence), "vkCreateFence");
    in_flight_ = gpu::UniqueFence(device, fence);
    VkSemaphoreCreateInfo sem_info{};
    sem_info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    VkSemaphore a = VK_NULL_HANDLE, b = VK_NULL_HANDLE;
    check(vkCreateSemaphore(device, &sem_info, nullptr, &a), "vkCreateSemaphore");
    check(vkCreateSemaphore(device, &sem_info, nullptr, &b), "vkCreateSemaphore");
    image_ready_ = gpu::UniqueSemaphore(device, a);
    render_done_ = gpu::UniqueSemaphore(device, b);
    create(extent, vsync);
}

Swapchain::~Swapchain() {
    wait_idle();
    destroy_targets();
}

void Swapchain::wait_idle() const {
    VkFence fence = in_flight_.get();
    vkWaitForFences(context_.device(), 1, &fence, VK_TRUE,
                    std::numeric_limits<std::uint64_t>::max());
}

void Swapchain::destroy_targets() {
    framebuffers_.clear();
    views_.clear();
    depth_view_.reset();
    depth_image_ = gpu::Image();
}

void Swapchain::recreate(VkExtent2D extent, bool vsync) {
    wait_idle();
    context_.wait_idle();
    destroy_targets();
    create(extent, vsync);
}

void Swapchain::create(VkExtent2D wanted, bool vsync) {
    const VkDevice device = context_.device();
    const VkPhysicalDevice physical = context_.physical_device();
    const VkSurfaceKHR surface = context_.surface();
    VkSurfaceCapabilitiesKHR caps{};
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    std::uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, formats.data());
    if (formats.empty()) throw gpu::GpuError("the window surface offers no image formats");
    VkSurfaceFormatKHR chosen = formats[0];
    for (const VkSurfaceFormatKHR& f : formats) {
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
            chosen = f;
            break;
        }
    }
    const bool recreate_pass = format_ != chosen.format;
    format_ = chosen.format;
    bgr_ = format_ == VK_FORMAT_B8G8R8A8_SRGB || format_ == VK_FORMAT_B8G8R8A8_UNORM;

    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always available: vsync
    if (!vsync) {
        vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, nullptr);
        std::vector<VkPresentModeKHR> modes(n);
        vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, modes.data());
        for (VkPresentModeKHR m : modes) {
            if (m == VK_PRESENT_MODE_IMMEDIATE_KHR || m == VK_PRESENT_MODE_MAILBOX_KHR) mode = m;
        }
    }
    extent_ = caps.currentExtent.width != std::numeric_limits<std::uint32_t>::max()
                  ? caps.currentExtent
                  : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width,
                                          caps.maxImageExtent.width),
                               std::clamp(wanted.height, caps.minImageExtent.height,
                                          caps.maxImageExtent.height)};
    std::uint32_t count = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{};

    info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    info.surface = surface;
    info.minImageCount = count;
    info.imageFormat = format_;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT)
        info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // screenshots
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_.get();
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    check(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain), "vkCreateSwapchainKHR");
    swapchain_ = UniqueSwapchain(device, swapchain);
    vkGetSwapchainImagesKHR(device, swapchain, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(device, swapchain, &n, images_.data());

    for (VkImage image : images_) {
        views_.push_back(
            gpu::create_image_view(device, image, format_, VK_IMAGE_ASPECT_COLOR_BIT, "swapchain"));
    }

    // Depth buffer.
    depth_image_ = gpu::Image(context_, {VK_FORMAT_D32_SFLOAT, extent_,
                                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth"});
    depth_view_ = gpu::create_image_view(device, depth_image_.get(), VK_FORMAT_D32_SFLOAT,
                                         VK_IMAGE_ASPECT_DEPTH_BIT, "depth");

    if (recreate_pass || !render_pass_) {
        VkAttachmentDescription att[2]{};
        att[0].format = format_;
        att[0].samples = VK_SAMPLE_COUNT_1_BIT;
        att[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        att[0].finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        att[1].format = VK_FORMAT_D32_SFLOAT;
        att[1].samples = VK_SAMPLE_COUNT_1_BIT;
        att[1].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[1].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att[1].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[1].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        att[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &colour_ref;
        sub.pDepthStencilAttachment = &depth_ref;
        VkSubpassDependency dep{};
        dep.srcSubpass = VK_SUBPASS_EXTERNAL;
        dep.dstSubpass = 0;
        dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                           VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
        dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                           VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
        dep.dstAccessMask =
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        VkRenderPassCreateInfo rp{};
        rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
        rp.attachmentCount = 2;
        rp.pAttachments = att;
        rp.subpassCount = 1;
        rp.pSubpasses = &sub;
        rp.dependencyCount = 1;
        rp.pDependencies = &dep;
        VkRenderPass pass = VK_NULL_HANDLE;
        check(vkCreateRenderPass(device, &rp, nullptr, &pass), "vkCreateRenderPass");
        render_pass_ = UniqueRenderPass(device, pass);
    }
    for (const gpu::UniqueImageView& view : views_) {
        const VkImageView attachments[] = {view.get(), depth_view_.get()};
        VkFramebufferCreateInfo fb{};
        fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        fb.renderPass = render_pass_.get();
        fb.attachmentCount = 2;
        fb.pAttachments = attachments;
        fb.width = extent_.width;
        fb.height = extent_.height;
        fb.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        check(vkCreateFramebuffer(device, &fb, nullptr, &framebuffer), "vkCreateFramebuffer");
        framebuffers_.emplace_back(device, framebuffer);
    }
}

bool Swapchain::begin_frame(const float clear[3]) {
    const VkDevice device = context_.device();
    VkFence fence = in_flight_.get();
    vkWaitForFences(device, 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max());
    const VkResult acquired =
        vkAcquireNextImageKHR(device, swapchain_.get(), std::numeric_limits<std::uint64_t>::max(),
                              image_ready_.get(), VK_NULL_HANDLE, &image_index_);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
    vkResetFences(device, 1, &fence);
    vkResetCommandBuffer(command_buffer_, 0);
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(command_buffer_, &begin), "vkBeginCommandBuffer");
    VkClearValue clears[2]{};
    clears[0].color = {{clear[0], clear[1], clear[2], 1.0f}};
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = render_pass_.get();
    rp.framebuffer = framebuffers_[image_index_].get();
    rp.renderArea = {{0, 0}, extent_};
    rp.clearValueCount = 2;
    rp.pClearValues = clears;
    vkCmdBeginRenderPass(command_buffer_, &rp, VK_SUBPASS_CONTENTS_INLINE);
    return true;
}

bool Swapchain::end_frame(bool capture) {
    vkCmdEndRenderPass(command_buffer_);
    const VkImage image = images_[image_index_];
    if (capture) {
        const VkDeviceSize bytes = VkDeviceSize{extent_.width} * extent_.height * 4;
        if (!readback_ || readback_.size() < bytes) {
            readback_ = gpu::Buffer(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    gpu::MemoryUse::Readback);
        }
        gpu::image_barrier(command_buffer_, image, VK_IMAGE_ASPECT_COLOR_BIT,
                           VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyImageToBuffer(command_buffer_, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               readback_.get(), 1, &region);
        gpu::image_barrier(
            command_buffer_, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
            VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        gpu::buffer_barrier(command_buffer_, readback_.get(), VK_PIPELINE_STAGE_TRANSFER_BIT,
                            VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                            VK_ACCESS_HOST_READ_BIT);
        captured_ = extent_;
    }
    check(vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");
    const VkSemaphore wait = image_ready_.get();
    const VkSemaphore signal = render_done_.get();
    const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &wait;
    submit.pWaitDstStageMask = &stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &command_buffer_;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signal;
    VkResult presented = VK_SUCCESS;
    {
        const std::lock_guard<std::mutex> lock(context_.queue_mutex());
        check(vkQueueSubmit(context_.queue(), 1, &submit, in_flight_.get()), "vkQueueSubmit");
        ++submissions_;
        const VkSwapchainKHR swapchain = swapchain_.get();
        VkPresentInfoKHR present{};
        present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &signal;
        present.swapchainCount = 1;
        present.pSwapchains = &swapchain;
        present.pImageIndices = &image_index_;
        presented = vkQueuePresentKHR(context_.queue(), &present);
    }
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) return false;
    check(presented, "vkQueuePresentKHR");
    return true;
}

PngImage Swapchain::screenshot() const {
    wait_idle();
    PngImage image;
    if (!readback_) throw gpu::GpuError("no frame was captured for the screenshot");
    readback_.invalidate(context_);
    image.width = captured_.width;
    image.height = captured_.height;
    image.channels = 3;
    image.bit_depth = 8;
    image.samples.resize(std::size_t{image.width} * image.height * 3);
    const auto* src = static_cast<const std::uint8_t*>(readback_.mapped());
    for (std::size_t i = 0; i < std::size_t{image.width} * image.height; ++i) {
        const std::uint8_t* p = src + 4 * i;
        image.samples[3 * i + 0] = bgr_ ? p[2] : p[0];
        image.samples[3 * i + 1] = p[1];
        image.samples[3 * i + 2] = bgr_ ? p[0] : p[2];
    }
    return image;
}

}  // namespace sandtin::editor
