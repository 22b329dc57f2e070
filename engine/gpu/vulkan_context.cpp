#include "gpu/vulkan_context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "gpu/device_selection.hpp"
#include "gpu/gpu_error.hpp"

namespace sandtin::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr std::size_t kKeptMessages = 16;

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT && user != nullptr) {
        static_cast<VulkanContext*>(user)->on_validation_message(
            data && data->pMessage ? data->pMessage : "(no message)");
    }
    return VK_FALSE;  // never abort the call: the count is what fails the test
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(VulkanContext* context) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = debug_callback;
    info.pUserData = context;
    return info;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

bool has_instance_extension(const std::string& name) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(),
                       [&](const VkExtensionProperties& e) { return name == e.extensionName; });
}

std::vector<std::string> device_extensions_of(VkPhysicalDevice pd) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
    std::vector<std::string> names;
    for (const auto& e : exts)
        names.emplace_back(e.extensionName);
    return names;
}

std::string version_string(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// The queue family sandtin uses on `pd`: graphics + compute (+ present to `surface`).
std::optional<uint32_t> universal_family(VkPhysicalDevice pd, VkSurfaceKHR surface) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) != need || families[i].queueCount == 0) continue;
        if (surface != VK_NULL_HANDLE) {
            VkBool32 present = VK_FALSE;
            if (vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present) != VK_SUCCESS ||
                !present) {
                continue;
            }
        }
        return i;
    }
    return std::nullopt;
}

}  // namespace

struct VulkanContext::DebugMessenger {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT handle = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy = nullptr;
    DebugMessenger() = default;
    DebugMessenger(const DebugMessenger&) = delete;
    DebugMessenger& operator=(const DebugMessenger&) = delete;
    ~DebugMessenger() {
        if (handle != VK_NULL_HANDLE && destroy != nullptr) destroy(instance, handle, nullptr);
    }
};

VulkanContext::VulkanContext(const ContextOptions& options)
    : max_dispatch_groups_x_(options.max_dispatch_groups_x) {
    create_instance(options);
    const std::vector<std::string> device_extensions = wanted_device_extensions(options);
    choose_physical_device(options, device_extensions);
    create_device(device_extensions);
}

// The instance, with the validation layer and its messenger when asked for, and the surface.
void VulkanContext::create_instance(const ContextOptions& options) {
    uint32_t loader_version = VK_API_VERSION_1_0;
    if (vkEnumerateInstanceVersion(&loader_version) != VK_SUCCESS ||
        loader_version < VK_API_VERSION_1_2) {
        throw GpuUnavailable("the Vulkan loader supports only Vulkan " +
                             version_string(loader_version) + "; sandtin needs 1.2");
    }
    std::vector<std::string> ext_names = options.instance_extensions;
    std::vector<const char*> layers;
    if (options.validation) {
        if (!has_layer(kValidationLayer)) {
            throw GpuError(std::string(kValidationLayer) +
                           " is not installed (Debian package vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        ext_names.emplace_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    if (options.make_surface) ext_names.emplace_back(VK_KHR_SURFACE_EXTENSION_NAME);
    std::sort(ext_names.begin(), ext_names.end());
    ext_names.erase(std::unique(ext_names.begin(), ext_names.end()), ext_names.end());
    std::vector<const char*> exts;
    for (const std::string& e : ext_names) {
        if (!has_instance_extension(e) &&
            !(options.validation && e == VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
            throw GpuUnavailable("Vulkan instance extension " + e + " is not available");
        }
        exts.push_back(e.c_str());
    }

    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = options.application_name.c_str();
    app.pEngineName = "sandtin";
    app.apiVersion = VK_API_VERSION_1_2;

    VkDebugUtilsMessengerCreateInfoEXT debug_info = messenger_info(this);
    VkInstanceCreateInfo ici{};
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = static_cast<uint32_t>(exts.size());
    ici.ppEnabledExtensionNames = exts.data();
    if (options.validation) ici.pNext = &debug_info;  // also catches create/destroy messages

    VkInstance instance = VK_NULL_HANDLE;
    const VkResult ir = vkCreateInstance(&ici, nullptr, &instance);
    if (ir == VK_ERROR_INCOMPATIBLE_DRIVER || ir == VK_ERROR_INITIALIZATION_FAILED) {
        throw GpuUnavailable(std::string("no Vulkan driver: vkCreateInstance returned ") +
                             result_name(ir));
    }
    check(ir, "vkCreateInstance");
    instance_ = UniqueInstance(instance);

    if (options.validation) {
        messenger_ = std::make_unique<DebugMessenger>();
        messenger_->instance = instance;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        messenger_->destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (create == nullptr || messenger_->destroy == nullptr) {
            throw GpuError("vkCreateDebugUtilsMessengerEXT is not available");
        }
        check(create(instance, &debug_info, nullptr, &messenger_->handle),
              "vkCreateDebugUtilsMessengerEXT");
    }

    if (options.make_surface) {
        VkSurfaceKHR surface = options.make_surface(instance);
        if (surface == VK_NULL_HANDLE) throw GpuError("the surface callback returned no surface");
        surface_ = UniqueSurface(instance, surface);
    }
}

std::vector<std::string> VulkanContext::wanted_device_extensions(const ContextOptions& options) {
    std::vector<std::string> wanted = options.device_extensions;
    if (options.make_surface) wanted.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    return wanted;
}

// The device the options, SANDTIN_DEVICE or the ranking pick among those that can run sandtin.
void VulkanContext::choose_physical_device(const ContextOptions& options,
                                           const std::vector<std::string>& wanted_device_exts) {
    uint32_t count = 0;
    const VkResult er = vkEnumeratePhysicalDevices(instance_.get(), &count, nullptr);
    if (er != VK_SUCCESS || count == 0) throw GpuUnavailable("no Vulkan physical device found");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance_.get(), &count, devices.data()),
          "vkEnumeratePhysicalDevices");
    devices.resize(count);

    std::vector<DeviceCandidate> candidates;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties p{};
        vkGetPhysicalDeviceProperties(pd, &p);
        DeviceCandidate c{p.deviceName, p.deviceType, p.apiVersion, true, {}};
        if (p.apiVersion < VK_API_VERSION_1_2) {
            c.usable = false;
            c.unusable_reason = "Vulkan " + version_string(p.apiVersion) + " < 1.2";
        } else if (!universal_family(pd, surface_.get())) {
            c.usable = false;
            c.unusable_reason = surface_ ? "no graphics+compute queue that can present"
                                         : "no graphics+compute queue";
        } else {
            const auto have = device_extensions_of(pd);
            for (const std::string& e : wanted_device_exts) {
                if (std::find(have.begin(), have.end(), e) == have.end()) {
                    c.usable = false;
                    c.unusable_reason = "missing device extension " + e;
                    break;
                }
            }
        }
        candidates.push_back(std::move(c));
    }
    std::optional<std::string> override_spec = options.device_override;
    if (!override_spec) {
        if (const char* env = std::getenv("SANDTIN_DEVICE"); env != nullptr && *env != '\0') {
            override_spec = std::string(env);
        }
    }
    const DeviceChoice choice = choose_device(candidates, override_spec);
    physical_device_ = devices[choice.index];
    selection_reason_ = choice.reason;
    vkGetPhysicalDeviceProperties(physical_device_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);
    queue_family_ = *universal_family(physical_device_, surface_.get());
    {
        uint32_t fc = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &fc, nullptr);
        std::vector<VkQueueFamilyProperties> families(fc);
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &fc, families.data());
        timestamp_valid_bits_ = families[queue_family_].timestampValidBits;
    }
}

// The logical device with the optional features the device has, its queue, and the pool and
// fence of one-shot submissions.
void VulkanContext::create_device(const std::vector<std::string>& wanted_device_exts) {
    VkPhysicalDeviceVulkan12Features have12{};
    have12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    VkPhysicalDeviceFeatures2 have{};
    have.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    have.pNext = &have12;
    vkGetPhysicalDeviceFeatures2(physical_device_, &have);

    VkPhysicalDeviceVulkan12Features want12{};
    want12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    want12.timelineSemaphore = have12.timelineSemaphore;
    want12.hostQueryReset = have12.hostQueryReset;
    VkPhysicalDeviceFeatures2 want{};
    want.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    want.pNext = &want12;
    want.features.fillModeNonSolid = have.features.fillModeNonSolid;
    want.features.samplerAnisotropy = have.features.samplerAnisotropy;
    want.features.wideLines = have.features.wideLines;
    features_.fill_mode_non_solid = have.features.fillModeNonSolid == VK_TRUE;
    features_.sampler_anisotropy = have.features.samplerAnisotropy == VK_TRUE;
    features_.wide_lines = have.features.wideLines == VK_TRUE;
    features_.timeline_semaphore = have12.timelineSemaphore == VK_TRUE;
    features_.host_query_reset = have12.hostQueryReset == VK_TRUE;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = queue_family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;

    std::vector<const char*> dexts;
    for (const std::string& e : wanted_device_exts)
        dexts.push_back(e.c_str());
    VkDeviceCreateInfo dci{};
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.pNext = &want;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<uint32_t>(dexts.size());
    dci.ppEnabledExtensionNames = dexts.data();
    VkDevice device = VK_NULL_HANDLE;
    check(vkCreateDevice(physical_device_, &dci, nullptr, &device), "vkCreateDevice");
    device_ = UniqueDevice(device);
    vkGetDeviceQueue(device, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = queue_family_;
    VkCommandPool pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(device, &pci, nullptr, &pool), "vkCreateCommandPool");
    one_shot_pool_ = UniqueCommandPool(device, pool);
    VkFenceCreateInfo fci{};
    fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    check(vkCreateFence(device, &fci, nullptr, &fence), "vkCreateFence");
    one_shot_fence_ = UniqueFence(device, fence);
}

VulkanContext::~VulkanContext() {
    if (device_) vkDeviceWaitIdle(device_.get());
}

std::string VulkanContext::device_type() const {
    return device_type_name(properties_.deviceType);
}

uint32_t VulkanContext::dispatch_groups_x() const {
    const uint32_t device = properties_.limits.maxComputeWorkGroupCount[0];
    return max_dispatch_groups_x_ == 0 ? device : std::min(device, max_dispatch_groups_x_);
}

std::string VulkanContext::describe() const {
    return device_name() + " (" + device_type() + ", Vulkan " +
           version_string(properties_.apiVersion) + ", " + selection_reason_ + ")";
}

std::vector<std::string> VulkanContext::validation_messages() const {
    std::lock_guard lock(messages_mutex_);
    return messages_;
}

void VulkanContext::on_validation_message(const char* message) {
    validation_count_.fetch_add(1);
    std::lock_guard lock(messages_mutex_);
    if (messages_.size() < kKeptMessages) messages_.emplace_back(message);
}

uint32_t VulkanContext::memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                    VkMemoryPropertyFlags preferred) const {
    std::optional<uint32_t> fallback;
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        if ((type_bits & (1u << i)) == 0) continue;
        const VkMemoryPropertyFlags f = memory_.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (!fallback) fallback = i;
    }
    if (!fallback) {
        throw GpuError("no Vulkan memory type with the required properties (flags " +
                       std::to_string(required) + ")");
    }
    return *fallback;
}

void VulkanContext::wait_idle() const {
    // Its failure (a lost device) is left to the next submission to report: this also runs
    // in destructors.
    const std::lock_guard lock(queue_mutex_);
    static_cast<void>(vkDeviceWaitIdle(device_.get()));
}

void VulkanContext::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
    // The pool and the fence are shared: host access to both must be externally synchronised.
    const std::lock_guard one_shot(one_shot_mutex_);
    VkDevice device = device_.get();
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = one_shot_pool_.get();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device, &ai, &cb), "vkAllocateCommandBuffers");
    struct Free {
        VkDevice d;
        VkCommandPool p;
        VkCommandBuffer c;
        ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
    } free_cb{device, one_shot_pool_.get(), cb};

    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    record(cb);
    check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");

    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    VkFence fence = one_shot_fence_.get();
    check(vkResetFences(device, 1, &fence), "vkResetFences");
    {
        std::lock_guard lock(queue_mutex_);
        check(vkQueueSubmit(queue_, 1, &si, fence), "vkQueueSubmit");
    }
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace sandtin::gpu
