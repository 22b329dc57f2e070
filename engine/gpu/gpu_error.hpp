#pragma once
// Errors raised by the Vulkan layer. GpuUnavailable means "no usable Vulkan device on this
// machine" (no loader, no driver, no device): callers fall back to the CPU path and tests skip.
// Every other failure is a GpuError and is a real bug or misconfiguration.

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace sandtin::gpu {

class GpuError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class GpuUnavailable : public GpuError {
  public:
    using GpuError::GpuError;
};

// Human-readable name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY").
const char* result_name(VkResult result);

// Throws GpuError("<what>: <result name>") unless result is VK_SUCCESS.
void check(VkResult result, const char* what);

}  // namespace sandtin::gpu
