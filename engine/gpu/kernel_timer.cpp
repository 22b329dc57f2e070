#include "gpu/kernel_timer.hpp"

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu {

KernelTimer::KernelTimer(const VulkanContext& context, uint32_t max_pairs)
    : device_(context.device()),
      period_ns_(context.timestamp_period_ns()),
      enabled_(context.timestamps_supported() && max_pairs > 0),
      max_pairs_(max_pairs) {
    if (!enabled_) return;
    VkQueryPoolCreateInfo qpci{};
    qpci.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qpci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qpci.queryCount = 2 * max_pairs;
    VkQueryPool pool = VK_NULL_HANDLE;
    check(vkCreateQueryPool(device_, &qpci, nullptr, &pool), "vkCreateQueryPool");
    pool_ = UniqueQueryPool(device_, pool);
    names_.reserve(max_pairs);
}

void KernelTimer::reset(VkCommandBuffer cb) {
    names_.clear();
    if (enabled_) vkCmdResetQueryPool(cb, pool_.get(), 0, 2 * max_pairs_);
}

uint32_t KernelTimer::begin(VkCommandBuffer cb, const std::string& kernel) {
    if (!enabled_ || names_.size() >= max_pairs_) return UINT32_MAX;
    const auto pair = static_cast<uint32_t>(names_.size());
    names_.push_back(kernel);
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 2 * pair);
    return pair;
}

void KernelTimer::end(VkCommandBuffer cb, uint32_t pair) {
    if (pair == UINT32_MAX) return;
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 2 * pair + 1);
}

void KernelTimer::collect() {
    if (!enabled_ || names_.empty()) return;
    std::vector<uint64_t> ticks(2 * names_.size());
    check(vkGetQueryPoolResults(device_, pool_.get(), 0, static_cast<uint32_t>(ticks.size()),
                                ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    for (size_t i = 0; i < names_.size(); ++i) {
        const uint64_t dt = ticks[2 * i + 1] >= ticks[2 * i] ? ticks[2 * i + 1] - ticks[2 * i] : 0;
        totals_[names_[i]] += static_cast<double>(dt) * period_ns_;
        counts_[names_[i]] += 1;
    }
    names_.clear();
}

void KernelTimer::clear() {
    totals_.clear();
    counts_.clear();
}

}  // namespace sandtin::gpu
