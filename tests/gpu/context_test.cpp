// VulkanContext, device choice and buffers.

#include <cstring>
#include <memory>
#include <numeric>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/device_selection.hpp"
#include "gpu_fixture.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;

std::vector<DeviceCandidate> three_devices() {
    return {
        {"llvmpipe (LLVM 15.0.6, 256 bits)",
         VK_PHYSICAL_DEVICE_TYPE_CPU,
         VK_API_VERSION_1_3,
         true,
         {}},
        {"Intel(R) UHD Graphics",
         VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
         VK_API_VERSION_1_3,
         true,
         {}},
        {"NVIDIA GeForce RTX", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_API_VERSION_1_3, true, {}}};
}

TEST(DeviceSelection, PrefersDiscreteThenIntegratedThenCpu) {
    auto devices = three_devices();
    EXPECT_EQ(choose_device(devices, std::nullopt).index, 2u);
    devices[2].usable = false;
    EXPECT_EQ(choose_device(devices, std::nullopt).index, 1u);
    devices[1].usable = false;
    const DeviceChoice cpu = choose_device(devices, std::nullopt);
    EXPECT_EQ(cpu.index, 0u);
    EXPECT_NE(cpu.reason.find("CPU"), std::string::npos);
}

TEST(DeviceSelection, OverrideByIndexAndByNameSubstring) {
    const auto devices = three_devices();
    EXPECT_EQ(choose_device(devices, std::string("0")).index, 0u);
    EXPECT_EQ(choose_device(devices, std::string("uhd")).index, 1u);
    EXPECT_EQ(choose_device(devices, std::string("LLVMPIPE")).index, 0u);
    EXPECT_NE(choose_device(devices, std::string("1")).reason.find("SANDTIN_DEVICE"),
              std::string::npos);
}

TEST(DeviceSelection, BadOverrideNamesTheDevices) {
    const auto devices = three_devices();
    try {
        choose_device(devices, std::string("radeon"));
        FAIL() << "expected GpuError";
    } catch (const GpuUnavailable&) {
        FAIL() << "a bad override is a user error, not a missing GPU";
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find("llvmpipe"), std::string::npos) << e.what();
    }
    EXPECT_THROW(choose_device(devices, std::string("7")), GpuError);
}

TEST(DeviceSelection, NoUsableDeviceIsUnavailable) {
    EXPECT_THROW(choose_device({}, std::nullopt), GpuUnavailable);
    auto devices = three_devices();
    for (auto& d : devices)
        d.usable = false;
    EXPECT_THROW(choose_device(devices, std::nullopt), GpuUnavailable);
}

TEST(DeviceSelection, PhysicsGoesToHardwareGpusAndStaysOnTheCpuOnASoftwareDevice) {
    EXPECT_TRUE(prefers_gpu_physics(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU));
    EXPECT_TRUE(prefers_gpu_physics(VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU));
    EXPECT_TRUE(prefers_gpu_physics(VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU));
    EXPECT_FALSE(prefers_gpu_physics(VK_PHYSICAL_DEVICE_TYPE_CPU));  // lavapipe
    EXPECT_FALSE(prefers_gpu_physics(VK_PHYSICAL_DEVICE_TYPE_OTHER));
}

TEST_F(GpuTest, ContextDescribesItsDevice) {
    EXPECT_FALSE(ctx().device_name().empty());
    EXPECT_NE(ctx().describe().find(ctx().device_name()), std::string::npos);
    EXPECT_GE(ctx().properties().apiVersion, VK_API_VERSION_1_2);
    EXPECT_NE(ctx().queue(), VK_NULL_HANDLE);
    EXPECT_EQ(ctx().surface(), VK_NULL_HANDLE);
}

TEST_F(GpuTest, UploadCopyReadbackRoundTrip) {
    const std::size_t n = 4096;
    std::vector<uint32_t> data(n);
    std::iota(data.begin(), data.end(), 7u);
    const VkDeviceSize bytes = n * sizeof(uint32_t);
    Buffer up(ctx(), bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    Buffer dev(ctx(), bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
               MemoryUse::Device);
    Buffer down(ctx(), bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    ASSERT_NE(up.mapped(), nullptr);
    EXPECT_EQ(dev.mapped(), nullptr);
    std::memcpy(up.mapped(), data.data(), bytes);
    ctx().submit_and_wait([&](VkCommandBuffer cb) {
        VkBufferCopy c{0, 0, bytes};
        vkCmdCopyBuffer(cb, up.get(), dev.get(), 1, &c);
        buffer_barrier(cb, dev.get(), VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        vkCmdCopyBuffer(cb, dev.get(), down.get(), 1, &c);
    });
    down.invalidate(ctx());
    std::vector<uint32_t> back(n);
    std::memcpy(back.data(), down.mapped(), bytes);
    EXPECT_EQ(back, data);
}

TEST_F(GpuTest, ZeroSizedBufferIsAClearError) {
    EXPECT_THROW(Buffer(ctx(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device), GpuError);
}

}  // namespace
}  // namespace sandtin::gpu

namespace sandtin::gpu {
namespace {

// The messenger must count real validation errors, or "validation clean" proves nothing.
TEST(ValidationMessenger, CountsAnInvalidCall) {
    ContextOptions options;
    options.validation = true;
    std::unique_ptr<VulkanContext> context;
    try {
        context = std::make_unique<VulkanContext>(options);
    } catch (const GpuUnavailable& e) {
        GTEST_SKIP() << "no Vulkan device: " << e.what();
    }
    EXPECT_EQ(context->validation_message_count(), 0u);
    VkBufferCreateInfo bci{};
    bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bci.size = 64;
    bci.usage = 0;  // invalid: VUID-VkBufferCreateInfo-None-09500 / usage-requiredbitmask
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult r = vkCreateBuffer(context->device(), &bci, nullptr, &buffer);
    if (r == VK_SUCCESS) vkDestroyBuffer(context->device(), buffer, nullptr);
    EXPECT_GE(context->validation_message_count(), 1u);
    ASSERT_FALSE(context->validation_messages().empty());
}

// The surface path itself (callback, present-capable family, swapchain extension) is covered
// by the editor's tests under Xvfb: this Mesa offers no VK_EXT_headless_surface.
TEST(SurfaceContext, NullSurfaceFromCallbackIsAClearError) {
    ContextOptions options;
    options.make_surface = [](VkInstance) { return VkSurfaceKHR{VK_NULL_HANDLE}; };
    try {
        VulkanContext context(options);
        FAIL() << "expected an error";
    } catch (const GpuUnavailable& e) {
        GTEST_SKIP() << "no Vulkan device: " << e.what();
    } catch (const GpuError& e) {
        EXPECT_NE(std::string(e.what()).find("surface"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sandtin::gpu
