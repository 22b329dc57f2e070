#include "editor_window.hpp"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <stdexcept>

#include "gpu/gpu_error.hpp"

namespace sandtin::editor {

EditorWindow::EditorWindow(int width, int height, bool validation, bool vsync, void* user,
                           const std::function<void(GLFWwindow*)>& install_callbacks) {
    if (glfwInit() != GLFW_TRUE) {
        throw std::runtime_error(
            "cannot open a window: no display (set DISPLAY, or run under "
            "xvfb-run -s '-screen 0 1280x720x24')");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(width, height, "sandtin", nullptr, nullptr);
    if (window_ == nullptr) {
        glfwTerminate();
        throw std::runtime_error("glfwCreateWindow failed");
    }
    glfwSetWindowUserPointer(window_, user);
    install_callbacks(window_);

    try {
        gpu::ContextOptions o;
        std::uint32_t n = 0;
        const char** ext = glfwGetRequiredInstanceExtensions(&n);
        if (ext == nullptr) throw std::runtime_error("GLFW finds no Vulkan surface support");
        o.instance_extensions.assign(ext, ext + n);
        GLFWwindow* win = window_;
        o.make_surface = [win](VkInstance instance) {
            VkSurfaceKHR surface = VK_NULL_HANDLE;
            if (glfwCreateWindowSurface(instance, win, nullptr, &surface) != VK_SUCCESS)
                return VkSurfaceKHR{VK_NULL_HANDLE};
            return surface;
        };
        o.validation = validation;
        context_ = std::make_unique<gpu::VulkanContext>(o);
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        swapchain_ = std::make_unique<Swapchain>(
            *context_, VkExtent2D{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
            vsync);
        renderer_ = std::make_unique<render::TerrainRenderer>(*context_, swapchain_->render_pass());

        // Dear ImGui's backends, on a descriptor pool of their own.
        const VkDevice device = context_->device();
        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
        VkDescriptorPoolCreateInfo pool{};
        pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        pool.maxSets = 16;
        pool.poolSizeCount = 1;
        pool.pPoolSizes = &size;
        VkDescriptorPool handle = VK_NULL_HANDLE;
        gpu::check(vkCreateDescriptorPool(device, &pool, nullptr, &handle),
                   "vkCreateDescriptorPool");
        imgui_pool_ = gpu::UniqueDescriptorPool(device, handle);
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; settings live in our file
        ImGui::StyleColorsDark();
        ImGui_ImplGlfw_InitForVulkan(window_, true);
        ImGui_ImplVulkan_InitInfo info{};
        info.Instance = context_->instance();
        info.PhysicalDevice = context_->physical_device();
        info.Device = device;
        info.QueueFamily = context_->queue_family();
        info.Queue = context_->queue();
        info.DescriptorPool = handle;
        info.MinImageCount = 2;
        info.ImageCount = std::max(2u, swapchain_->image_count());
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        ImGui_ImplVulkan_Init(&info, swapchain_->render_pass());
        imgui_ready_ = true;
        context_->submit_and_wait(
            [](VkCommandBuffer cb) { ImGui_ImplVulkan_CreateFontsTexture(cb); });
        ImGui_ImplVulkan_DestroyFontUploadObjects();
    } catch (...) {
        teardown();  // the members' own destructors then find nothing left to do
        throw;
    }
}

EditorWindow::~EditorWindow() {
    teardown();
}

void EditorWindow::teardown() {
    if (context_) context_->wait_idle();
    if (imgui_ready_) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        imgui_ready_ = false;
    }
    renderer_.reset();
    imgui_pool_.reset();
    swapchain_.reset();
    context_.reset();
    if (window_ != nullptr) {
        glfwDestroyWindow(window_);
        window_ = nullptr;
        glfwTerminate();
    }
}

void EditorWindow::wait_idle() const {
    if (context_) context_->wait_idle();
}

void EditorWindow::fit_swapchain(bool vsync) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    const VkExtent2D e = swapchain_->extent();
    if (w > 0 && h > 0 &&
        (static_cast<std::uint32_t>(w) != e.width || static_cast<std::uint32_t>(h) != e.height))
        swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)}, vsync);
}

void EditorWindow::recreate_swapchain(bool vsync) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w > 0 && h > 0)
        swapchain_->recreate({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)}, vsync);
}

}  // namespace sandtin::editor
