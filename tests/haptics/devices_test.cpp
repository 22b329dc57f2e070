// The simulated device (replay and mouse spring) and the UDP device on loopback, driven by
// hand without the loop thread.

#include <gtest/gtest.h>

#include <chrono>
#include <limits>
#include <thread>

#include "haptics/simulated_device.hpp"
#include "haptics/udp_device.hpp"
#include "haptics/udp_protocol.hpp"
#include "haptics/udp_socket.hpp"

namespace sandtin::haptics {
namespace {

TEST(SimulatedDevice, ReplaysThenReportsLoss) {
    Trajectory t;
    t.samples = {{{0.1, 0.2, 0.3}, 0}, {{0.4, 0.5, 0.6}, 1}};
    SimulatedDevice d = SimulatedDevice::replay(t);
    d.open();
    DeviceState s;
    ASSERT_EQ(d.read(s), ReadStatus::Ok);
    EXPECT_EQ(s.position, (Vec3{0.1, 0.2, 0.3}));
    d.write_force({{0, 0, 20.0}, true, false});  // clamped to 10 N
    ASSERT_EQ(d.read(s), ReadStatus::Ok);
    EXPECT_EQ(s.buttons, 1u);
    d.write_force({{1, 0, 0}, true, false});
    EXPECT_EQ(d.read(s), ReadStatus::Lost);
    d.close();
    ASSERT_EQ(d.forces().size(), 2u);
    EXPECT_EQ(d.forces()[0], (Vec3{0, 0, 10.0}));
}

TEST(SimulatedDevice, SpringFollowsTheTargetAndYieldsToForce) {
    SpringParams p;
    SimulatedDevice d = SimulatedDevice::spring(p, {0.5, 0.5, 0.1});
    d.open();
    d.set_target({0.6, 0.5, 0.1});
    DeviceState s;
    for (int i = 0; i < 2000; ++i)
        ASSERT_EQ(d.read(s), ReadStatus::Ok);
    EXPECT_NEAR(s.position.x, 0.6, 1e-6);  // critically damped: settled after 2 s
    // A constant 2 N push along +z: equilibrium offset F / k = 2 / 400 = 5 mm.
    for (int i = 0; i < 3000; ++i) {
        d.write_force({{0, 0, 2.0}, true, false});
        ASSERT_EQ(d.read(s), ReadStatus::Ok);
    }
    EXPECT_NEAR(s.position.z, 0.105, 1e-6);
    EXPECT_THROW(SimulatedDevice::spring({0.0}, {}), std::invalid_argument);
}

// Receives from `socket` for up to a second.
std::optional<Packet> receive_packet(UdpSocket& socket) {
    std::array<std::uint8_t, 128> buf{};
    for (int i = 0; i < 100; ++i) {
        if (auto n = socket.receive(buf, nullptr, 10))
            return decode_packet(std::span(buf.data(), *n));
    }
    return std::nullopt;
}

/// Reads the device until it has received `n` datagrams (about 200 ms at most): the state it
/// read last goes to `s`, and its counters are returned.
UdpDeviceCounters read_until_received(UdpDevice& device, DeviceState& s, std::uint64_t n) {
    for (int i = 0; i < 200 && device.counters().received < n; ++i) {
        EXPECT_EQ(device.read(s), ReadStatus::Ok);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return device.counters();
}

TEST(UdpDevice, LoopbackRoundTripDropsMalformedAndLatePackets) {
    UdpDevice device;
    device.open();
    ASSERT_NE(device.port(), 0);
    UdpSocket driver = UdpSocket::bind(0);
    const UdpEndpoint to{0x7F000001u, device.port()};

    DeviceState s;
    ASSERT_EQ(device.read(s), ReadStatus::Ok);
    EXPECT_FALSE(s.valid);                         // nothing yet
    device.write_force({{0, 0, 1}, true, false});  // no peer: nothing sent
    EXPECT_EQ(device.counters().forces_sent, 0u);

    const std::vector<std::uint8_t> garbage = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13};
    ASSERT_TRUE(driver.send_to(garbage, to));
    ASSERT_TRUE(driver.send_to(encode_packet({5, PosePacket{{0.1, 0.2, 0.3}, 1}}), to));
    ASSERT_TRUE(driver.send_to(encode_packet({4, PosePacket{{9, 9, 9}, 0}}), to));  // late
    ASSERT_TRUE(driver.send_to(encode_packet({6, ForcePacket{}}), to));  // wrong direction
    std::vector<std::uint8_t> big(300, 0);
    ASSERT_TRUE(driver.send_to(big, to));  // oversized
    // Loopback delivery is immediate but not synchronous: read until all five arrived.
    const UdpDeviceCounters c = read_until_received(device, s, 5);
    EXPECT_EQ(c.received, 5u);
    EXPECT_EQ(c.poses, 1u);
    EXPECT_EQ(c.malformed, 3u);
    EXPECT_EQ(c.out_of_order, 1u);
    ASSERT_TRUE(s.valid);
    EXPECT_EQ(s.position, (Vec3{0.1, 0.2, 0.3}));
    EXPECT_EQ(s.sequence, 5u);

    device.write_force({{0.5, -0.5, 3.25}, true, false});
    const std::optional<Packet> reply = receive_packet(driver);
    ASSERT_TRUE(reply.has_value());
    const auto& f = std::get<ForcePacket>(reply->body);
    EXPECT_EQ(f.ack, 5u);
    EXPECT_EQ(f.flags, kForceFlagContact);
    EXPECT_EQ(f.force, (Vec3{0.5, -0.5, 3.25}));

    ASSERT_TRUE(driver.send_to(encode_packet({7, ByePacket{}}), to));
    ReadStatus status = ReadStatus::Ok;
    for (int i = 0; i < 200 && status == ReadStatus::Ok; ++i) {
        status = device.read(s);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(status, ReadStatus::Lost);
    EXPECT_TRUE(device.counters().bye);
    device.close();
}

TEST(UdpDevice, OutOfRangePosesAreDroppedAndCountedAsMalformed) {
    // A driver glitch: a finite height beyond kMaxHeight (1e9 m). Dropped like a NaN: the
    // device keeps the last good pose and counts the packet as malformed.
    UdpDevice device;
    device.open();
    UdpSocket driver = UdpSocket::bind(0);
    const UdpEndpoint to{0x7F000001u, device.port()};
    ASSERT_TRUE(driver.send_to(encode_packet({1, PosePacket{{0.5, 0.5, 0.2}, 0}}), to));
    ASSERT_TRUE(driver.send_to(encode_packet({2, PosePacket{{0.5, 0.5, -2e9}, 0}}), to));
    ASSERT_TRUE(driver.send_to(encode_packet({3, PosePacket{{1e300, 1e300, -1e300}, 1}}), to));
    ASSERT_TRUE(driver.send_to(
        encode_packet({4, PosePacket{{0.5, std::numeric_limits<double>::quiet_NaN(), 0.2}, 0}}),
        to));
    DeviceState s;
    UdpDeviceCounters c = read_until_received(device, s, 4);
    EXPECT_EQ(c.received, 4u);
    EXPECT_EQ(c.poses, 1u);
    EXPECT_EQ(c.malformed, 3u);
    ASSERT_TRUE(s.valid);
    EXPECT_EQ(s.position, (Vec3{0.5, 0.5, 0.2}));
    EXPECT_EQ(s.sequence, 1u);
    // The stream goes on: the next good pose is taken.
    ASSERT_TRUE(driver.send_to(encode_packet({5, PosePacket{{0.4, 0.5, 0.1}, 1}}), to));
    for (int i = 0; i < 200 && device.counters().poses < 2; ++i) {
        ASSERT_EQ(device.read(s), ReadStatus::Ok);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    c = device.counters();
    EXPECT_EQ(c.poses, 2u);
    EXPECT_EQ(c.malformed, 3u);
    EXPECT_EQ(s.position, (Vec3{0.4, 0.5, 0.1}));
    EXPECT_EQ(s.sequence, 5u);
}

TEST(UdpDevice, ARestartedDriverStartsANewStream) {
    UdpDevice device;
    device.open();
    const UdpEndpoint to{0x7F000001u, device.port()};
    DeviceState s;
    {
        UdpSocket first = UdpSocket::bind(0);
        ASSERT_TRUE(first.send_to(encode_packet({900, PosePacket{{0.1, 0.1, 0.1}, 0}}), to));
        for (int i = 0; i < 200 && device.counters().poses < 1; ++i) {
            ASSERT_EQ(device.read(s), ReadStatus::Ok);
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    UdpSocket second = UdpSocket::bind(0);  // numbers from 1 again
    ASSERT_TRUE(second.send_to(encode_packet({1, PosePacket{{0.2, 0.2, 0.2}, 0}}), to));
    for (int i = 0; i < 200 && device.counters().poses < 2; ++i) {
        ASSERT_EQ(device.read(s), ReadStatus::Ok);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(device.counters().poses, 2u);
    EXPECT_EQ(device.counters().driver_changes, 1u);
    EXPECT_EQ(s.position, (Vec3{0.2, 0.2, 0.2}));
    device.write_force({{0, 0, 1}, true, false});
    const std::optional<Packet> reply = receive_packet(second);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(std::get<ForcePacket>(reply->body).ack, 1u);
}

TEST(UdpDevice, SilenceAfterTheFirstPoseIsDeviceLoss) {
    UdpDeviceConfig config;
    config.loss_timeout_ns = 20'000'000;
    UdpDevice device(config);
    device.open();
    UdpSocket driver = UdpSocket::bind(0);
    ASSERT_TRUE(driver.send_to(encode_packet({1, PosePacket{{0.1, 0.2, 0.3}, 0}}),
                               {0x7F000001u, device.port()}));
    DeviceState s;
    ReadStatus status = ReadStatus::Ok;
    for (int i = 0; i < 1000 && status == ReadStatus::Ok; ++i) {
        status = device.read(s);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_EQ(status, ReadStatus::Lost);
    EXPECT_TRUE(device.counters().timed_out);
}

TEST(UdpSocket, RejectsBadAddresses) {
    EXPECT_THROW(parse_ipv4("300.1.1.1"), std::invalid_argument);
    EXPECT_EQ(parse_ipv4("127.0.0.1"), 0x7F000001u);
    UdpSocket a = UdpSocket::bind(0);
    EXPECT_THROW(UdpSocket::bind(a.port()), std::runtime_error);  // port taken
}

}  // namespace
}  // namespace sandtin::haptics
