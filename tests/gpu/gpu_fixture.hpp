#pragma once
// Shared Vulkan context for the GPU tests, with the validation layer on. Tests are skipped
// (GTEST_SKIP with the reason) only when the machine has no Vulkan device at all; every
// validation message emitted during a test fails that test.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "gpu/gpu_error.hpp"
#include "gpu/vulkan_context.hpp"

namespace sandtin::gpu::testing {

struct SharedContext {
    std::unique_ptr<VulkanContext> context;
    std::string unavailable_reason;
};

// Created on first use, destroyed at exit. GpuUnavailable is recorded; other errors propagate.
inline SharedContext& shared_context() {
    static SharedContext shared = [] {
        SharedContext s;
        try {
            ContextOptions options;
            options.validation = true;
            s.context = std::make_unique<VulkanContext>(options);
        } catch (const GpuUnavailable& e) {
            s.unavailable_reason = e.what();
        }
        return s;
    }();
    return shared;
}

class GpuTest : public ::testing::Test {
  protected:
    void SetUp() override {
        SharedContext& s = shared_context();
        if (!s.context) GTEST_SKIP() << "no Vulkan device: " << s.unavailable_reason;
        ctx_ = s.context.get();
        messages_before_ = ctx_->validation_message_count();
    }
    void TearDown() override {
        if (ctx_ == nullptr) return;
        const uint64_t after = ctx_->validation_message_count();
        if (after != messages_before_) {
            std::string all;
            for (const std::string& m : ctx_->validation_messages())
                all += "\n  " + m;
            ADD_FAILURE() << (after - messages_before_) << " validation message(s):" << all;
        }
    }
    VulkanContext& ctx() { return *ctx_; }

  private:
    VulkanContext* ctx_ = nullptr;
    uint64_t messages_before_ = 0;
};

}  // namespace sandtin::gpu::testing
