#pragma once
// One Vulkan instance + device + queue for sandtin, headless or with a presentation surface.
//
// Headless (CLI, tests, benchmarks): VulkanContext ctx({});
// With a window (editor): pass the window system's instance extensions and a callback that
// creates the surface once the instance exists, e.g. with GLFW (in editor/, never in engine/):
//     ContextOptions o;
//     o.instance_extensions = /* glfwGetRequiredInstanceExtensions */;
//     o.make_surface = [win](VkInstance i) { VkSurfaceKHR s; glfwCreateWindowSurface(i, win,
//                                           nullptr, &s); return s; };
//     VulkanContext ctx(o);   // VK_KHR_swapchain is enabled on the device automatically.
//
// The context owns the surface and destroys it before the instance. It picks one queue family
// that supports graphics + compute (+ present when a surface exists) and creates one queue from
// it: every submission in sandtin goes to that queue. VkQueue is externally synchronised, so
// callers that submit from several threads must hold queue_mutex(); submit_and_wait() and
// wait_idle() take it themselves, and may be called from any thread (the editor uploads an
// opened scene on a worker while the UI thread draws).
//
// Device choice: discrete > integrated > virtual > CPU; SANDTIN_DEVICE (index or name
// substring) overrides. Throws GpuUnavailable when there is no Vulkan device at all.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "gpu/vk_handle.hpp"

namespace sandtin::gpu {

struct ContextOptions {
    // Enables VK_LAYER_KHRONOS_validation and a debug messenger counting warnings and errors.
    // When the layer is not installed, construction throws GpuError naming the package.
    bool validation = false;
    // Extra instance extensions (e.g. from glfwGetRequiredInstanceExtensions).
    std::vector<std::string> instance_extensions;
    // Extra device extensions. VK_KHR_swapchain is added when make_surface is set.
    std::vector<std::string> device_extensions;
    // Creates the presentation surface from the instance; null for headless. The returned
    // surface is owned (and destroyed) by the context.
    std::function<VkSurfaceKHR(VkInstance)> make_surface;
    // Device override; when unset, the SANDTIN_DEVICE environment variable is used.
    std::optional<std::string> device_override;
    std::string application_name = "sandtin";
    // Caps the workgroups a direct dispatch puts along x below the device's own limit (0: the
    // device's). Tests set a small cap to run large-dispatch splitting on small meshes.
    uint32_t max_dispatch_groups_x = 0;
};

// Features enabled on the device when supported (queried, never required beyond Vulkan 1.2).
struct EnabledFeatures {
    bool fill_mode_non_solid = false;  // wireframe rendering
    bool sampler_anisotropy = false;
    bool wide_lines = false;
    bool timeline_semaphore = false;
    bool host_query_reset = false;
};

class VulkanContext {
  public:
    explicit VulkanContext(const ContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_.get(); }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_.get(); }
    VkQueue queue() const { return queue_; }
    // The family of queue(): graphics + compute + transfer (+ present when surface() exists).
    uint32_t queue_family() const { return queue_family_; }
    VkSurfaceKHR surface() const { return surface_.get(); }
    std::mutex& queue_mutex() const { return queue_mutex_; }

    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
    const EnabledFeatures& features() const { return features_; }
    std::string device_name() const { return properties_.deviceName; }
    std::string device_type() const;
    // Why this device was chosen ("discrete GPU preferred", "SANDTIN_DEVICE=1").
    const std::string& selection_reason() const { return selection_reason_; }
    // One line: "<name> (<type>, Vulkan x.y.z, <reason>)".
    std::string describe() const;

    // Nanoseconds per timestamp tick, and whether queue() supports timestamps.
    double timestamp_period_ns() const { return properties_.limits.timestampPeriod; }
    bool timestamps_supported() const { return timestamp_valid_bits_ != 0; }

    // Workgroups a direct dispatch may put along x and y (the device's limits, x capped by
    // ContextOptions::max_dispatch_groups_x).
    uint32_t dispatch_groups_x() const;
    uint32_t dispatch_groups_y() const { return properties_.limits.maxComputeWorkGroupCount[1]; }

    // Validation messages (warning or error severity) seen since construction; 0 when
    // validation is off. Thread-safe.
    uint64_t validation_message_count() const { return validation_count_.load(); }
    // The first messages (at most 16), for test failure output.
    std::vector<std::string> validation_messages() const;

    // Index of a memory type with all `required` flags among `type_bits`, preferring one that
    // also has `preferred`; throws GpuError when none exists.
    uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                         VkMemoryPropertyFlags preferred = 0) const;

    // Records commands with `record` into a one-time command buffer, submits to queue() and
    // waits for completion. For uploads, read-backs and tests; per-frame work uses its own
    // command buffers. Any thread: calls from two threads take turns (the one-shot pool and
    // fence are shared), so `record` must not call it again.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;
    // vkDeviceWaitIdle under queue_mutex(): waiting for the device is a use of its queue.
    // Never throws (it runs in destructors); a lost device fails the next submission.
    void wait_idle() const;

    // Called by the debug messenger.
    void on_validation_message(const char* message);

  private:
    struct DebugMessenger;

    // The construction's steps, in order.
    void create_instance(const ContextOptions& options);
    static std::vector<std::string> wanted_device_extensions(const ContextOptions& options);
    void choose_physical_device(const ContextOptions& options,
                                const std::vector<std::string>& wanted_device_exts);
    void create_device(const std::vector<std::string>& wanted_device_exts);

    // Declared first so they outlive the instance: the layer may still report while the
    // instance is destroyed.
    std::atomic<uint64_t> validation_count_{0};
    mutable std::mutex messages_mutex_;
    std::vector<std::string> messages_;

    UniqueInstance instance_;
    std::unique_ptr<DebugMessenger> messenger_;
    UniqueSurface surface_;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    UniqueDevice device_;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    uint32_t timestamp_valid_bits_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    EnabledFeatures features_;
    std::string selection_reason_;
    uint32_t max_dispatch_groups_x_ = 0;
    UniqueCommandPool one_shot_pool_;
    UniqueFence one_shot_fence_;

    mutable std::mutex one_shot_mutex_;  ///< held for a whole submit_and_wait()
    mutable std::mutex queue_mutex_;     ///< taken after one_shot_mutex_, never before
};

}  // namespace sandtin::gpu
