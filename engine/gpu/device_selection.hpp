#pragma once
// Choosing a physical device: discrete GPU, then integrated, then virtual, then CPU (lavapipe).
// Pure logic over a description of the candidates, so it is testable without hardware.
// An override string (SANDTIN_DEVICE) selects by index ("1") or by case-insensitive name
// substring ("llvmpipe"); an override that matches nothing is an error naming the candidates.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sandtin::gpu {

struct DeviceCandidate {
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    uint32_t api_version = 0;
    // False when the device lacks something sandtin needs (Vulkan 1.2, a compute+graphics
    // queue, presentation to the requested surface); `unusable_reason` says what.
    bool usable = true;
    std::string unusable_reason;
};

struct DeviceChoice {
    std::size_t index = 0;
    std::string reason;  // "discrete GPU preferred", "SANDTIN_DEVICE=llvmpipe", ...
};

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
const char* device_type_name(VkPhysicalDeviceType type);

// Rank: lower is preferred.
int device_type_rank(VkPhysicalDeviceType type);

// Whether the terrain's physics runs on this device when nobody chose (the editor's Auto, the
// CLI's --physics auto): on a hardware GPU (discrete, integrated, virtual), yes; on a CPU device
// (lavapipe), no: there the CPU solver is the faster one (`sandtin bench gpu`) and exact in
// double precision.
bool prefers_gpu_physics(VkPhysicalDeviceType type);

// Picks a device. Throws GpuUnavailable when no candidate is usable, GpuError when the
// override matches no usable device.
DeviceChoice choose_device(const std::vector<DeviceCandidate>& candidates,
                           const std::optional<std::string>& override_spec);

}  // namespace sandtin::gpu
