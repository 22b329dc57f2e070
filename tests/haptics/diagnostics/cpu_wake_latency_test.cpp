// The PM QoS request writes the latency as a binary 32-bit integer and keeps the file open
// until destroyed; a device it cannot open is a reported refusal. Tested on a plain file
// standing in for /dev/cpu_dma_latency (the real device would change the machine's idle).

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "haptics/diagnostics/cpu_wake_latency.hpp"

namespace sandtin::haptics {
namespace {

std::string temp_device() {
    char name[] = "/tmp/sandtin_pmqos_XXXXXX";
    const int fd = mkstemp(name);
    EXPECT_GE(fd, 0);
    close(fd);
    return name;
}

std::vector<char> contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(CpuWakeLatency, WritesTheLatencyAsABinaryIntAndHoldsTheFile) {
    const std::string device = temp_device();
    {
        const CpuWakeLatencyHold hold(0, device.c_str());
        EXPECT_TRUE(hold.held());
        EXPECT_EQ(hold.error(), "");
        const std::vector<char> bytes = contents(device);
        ASSERT_EQ(bytes.size(), sizeof(std::int32_t));
        std::int32_t value = -1;
        std::memcpy(&value, bytes.data(), sizeof value);
        EXPECT_EQ(value, 0);
    }
    const CpuWakeLatencyHold hold(25, device.c_str());
    std::int32_t value = -1;
    const std::vector<char> bytes = contents(device);
    ASSERT_EQ(bytes.size(), sizeof(std::int32_t));
    std::memcpy(&value, bytes.data(), sizeof value);
    EXPECT_EQ(value, 25);
    std::remove(device.c_str());
}

TEST(CpuWakeLatency, ADeviceThatCannotBeOpenedIsAReportedRefusal) {
    const CpuWakeLatencyHold hold(0, "/nonexistent/sandtin/cpu_dma_latency");
    EXPECT_FALSE(hold.held());
    EXPECT_NE(hold.error().find("/nonexistent/sandtin/cpu_dma_latency"), std::string::npos);
    EXPECT_NE(hold.error().find("No such file"), std::string::npos);
}

TEST(CpuWakeLatency, ANegativeLatencyIsRefused) {
    const std::string device = temp_device();
    const CpuWakeLatencyHold hold(-1, device.c_str());
    EXPECT_FALSE(hold.held());
    EXPECT_NE(hold.error().find(">= 0"), std::string::npos);
    EXPECT_TRUE(contents(device).empty());
    std::remove(device.c_str());
}

}  // namespace
}  // namespace sandtin::haptics
