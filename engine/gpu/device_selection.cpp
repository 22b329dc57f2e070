#include "gpu/device_selection.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "gpu/gpu_error.hpp"

namespace sandtin::gpu {

const char* device_type_name(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "CPU";
        default:
            return "other";
    }
}

bool prefers_gpu_physics(VkPhysicalDeviceType type) {
    return type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
           type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ||
           type == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU;
}

int device_type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string describe(const std::vector<DeviceCandidate>& candidates) {
    std::string out;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const DeviceCandidate& c = candidates[i];
        out += "\n  [" + std::to_string(i) + "] " + c.name + " (" + device_type_name(c.type) + ")";
        if (!c.usable) out += " unusable: " + c.unusable_reason;
    }
    return out;
}

}  // namespace

DeviceChoice choose_device(const std::vector<DeviceCandidate>& candidates,
                           const std::optional<std::string>& override_spec) {
    const bool any_usable = std::any_of(candidates.begin(), candidates.end(),
                                        [](const DeviceCandidate& c) { return c.usable; });
    if (!any_usable) {
        throw GpuUnavailable(candidates.empty()
                                 ? std::string("no Vulkan physical device found")
                                 : "no usable Vulkan device:" + describe(candidates));
    }

    if (override_spec && !override_spec->empty()) {
        const std::string& spec = *override_spec;
        std::size_t index = 0;
        const auto [end, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
        if (ec == std::errc() && end == spec.data() + spec.size()) {
            if (index >= candidates.size()) {
                throw GpuError("SANDTIN_DEVICE=" + spec +
                               " is out of range; devices:" + describe(candidates));
            }
            if (!candidates[index].usable) {
                throw GpuError("SANDTIN_DEVICE=" + spec +
                               " selects an unusable device:" + describe(candidates));
            }
            return {index, "SANDTIN_DEVICE=" + spec};
        }
        const std::string needle = lower(spec);
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            if (candidates[i].usable &&
                lower(candidates[i].name).find(needle) != std::string::npos) {
                return {i, "SANDTIN_DEVICE=" + spec};
            }
        }
        throw GpuError("SANDTIN_DEVICE=" + spec +
                       " matches no usable device; devices:" + describe(candidates));
    }

    std::size_t best = candidates.size();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (!candidates[i].usable) continue;
        if (best == candidates.size() ||
            device_type_rank(candidates[i].type) < device_type_rank(candidates[best].type)) {
            best = i;
        }
    }
    return {best, std::string(device_type_name(candidates[best].type)) + " preferred"};
}

}  // namespace sandtin::gpu
