#pragma once
// GPU time per kernel from timestamp queries: each timed dispatch writes a timestamp before
// and after itself; results are summed per kernel name after the submission completes.
// Inert (records nothing) when the queue has no timestamp support.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gpu/vk_handle.hpp"

namespace sandtin::gpu {

class VulkanContext;

class KernelTimer {
  public:
    // Room for `max_pairs` timed dispatches per submission.
    KernelTimer(const VulkanContext& context, uint32_t max_pairs);

    bool enabled() const { return enabled_; }
    // Resets the pool for a new command buffer (must be recorded outside dispatch pairs).
    void reset(VkCommandBuffer cb);
    // Returns the pair index, or UINT32_MAX when out of room or disabled.
    uint32_t begin(VkCommandBuffer cb, const std::string& kernel);
    void end(VkCommandBuffer cb, uint32_t pair);
    // After the submission completed: adds each pair's duration to totals (ns).
    void collect();

    const std::map<std::string, double>& totals_ns() const { return totals_; }
    const std::map<std::string, uint64_t>& counts() const { return counts_; }
    void clear();

  private:
    VkDevice device_;
    double period_ns_;
    bool enabled_;
    uint32_t max_pairs_;
    UniqueQueryPool pool_;
    std::vector<std::string> names_;
    std::map<std::string, double> totals_;
    std::map<std::string, uint64_t> counts_;
};

}  // namespace sandtin::gpu
