#pragma once
// The editor's window and what draws into it: a GLFW window, the Vulkan context on its
// surface, the swapchain, the terrain renderer and Dear ImGui's GLFW and Vulkan backends, made
// in order and torn down in the reverse order (the device outlives everything made on it).

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <functional>
#include <memory>

#include "gpu/render/terrain_renderer.hpp"
#include "gpu/vk_handle.hpp"
#include "gpu/vulkan_context.hpp"
#include "swapchain.hpp"

namespace sandtin::editor {

class EditorWindow {
  public:
    /// Opens a `width` x `height` window (screen pixels) whose GLFW user pointer is `user`;
    /// `install_callbacks` runs before ImGui's backend, which chains to the callbacks it finds.
    /// Throws std::runtime_error naming the problem (no display, no Vulkan surface).
    EditorWindow(int width, int height, bool validation, bool vsync, void* user,
                 const std::function<void(GLFWwindow*)>& install_callbacks);
    ~EditorWindow();
    EditorWindow(const EditorWindow&) = delete;
    EditorWindow& operator=(const EditorWindow&) = delete;

    GLFWwindow* glfw() const { return window_; }
    gpu::VulkanContext& context() { return *context_; }
    const gpu::VulkanContext& context() const { return *context_; }
    Swapchain& swapchain() { return *swapchain_; }
    const Swapchain& swapchain() const { return *swapchain_; }
    render::TerrainRenderer& renderer() { return *renderer_; }
    const render::TerrainRenderer& renderer() const { return *renderer_; }

    /// Waits until the GPU uses nothing (before objects a frame may read are destroyed).
    void wait_idle() const;
    /// The swapchain follows the framebuffer's size (not every presentation engine reports
    /// an out-of-date swapchain) and `vsync`.
    void fit_swapchain(bool vsync);
    /// Rebuilds the swapchain for the framebuffer as it is (it was out of date, or the
    /// present mode changed); nothing while the window is minimised.
    void recreate_swapchain(bool vsync);
    /// Window and framebuffer sizes (screen pixels, pixels).
    void window_size(int& w, int& h) const { glfwGetWindowSize(window_, &w, &h); }
    void framebuffer_size(int& w, int& h) const { glfwGetFramebufferSize(window_, &w, &h); }

  private:
    /// ImGui, the renderer, the swapchain, the device and the window, in that order.
    void teardown();

    GLFWwindow* window_ = nullptr;
    std::unique_ptr<gpu::VulkanContext> context_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<render::TerrainRenderer> renderer_;
    gpu::UniqueDescriptorPool imgui_pool_;
    bool imgui_ready_ = false;
};

}  // namespace sandtin::editor
