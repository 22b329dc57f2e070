#pragma once
// The network device: sandtin's end of the UDP protocol (udp_protocol.hpp). A driver process
// that owns the hardware sends pose packets to our port; each tick we answer the latest
// sender with a force packet that acknowledges the newest pose we used.
//
// Each read() drains every datagram waiting (up to a bound), so the loop always uses the
// newest pose. One driver at a time: a well-formed packet from another address or port than
// the current driver's starts a new stream (a restarted driver numbers from 1 again), and
// forces go to the new sender. Malformed packets and packets older than the newest accepted one are
// dropped and counted. The device is Lost (the loop stops) on a bye packet, or when no valid pose
// has arrived for `loss_timeout_ns` after the first one. Before the first pose the state is invalid
// and the loop renders no force.

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "haptics/haptic_device.hpp"
#include "haptics/sequence_filter.hpp"
#include "haptics/udp_socket.hpp"

namespace sandtin::haptics {

struct UdpDeviceConfig {
    std::uint16_t port = 0;                      ///< 0 = any free port (see UdpDevice::port())
    std::uint32_t address = 0x7F000001u;         ///< bind address, loopback by default
    double max_force = 10.0;                     ///< N, what the driver says its hardware renders
    std::int64_t loss_timeout_ns = 500'000'000;  ///< silence after the first pose = lost
    int max_datagrams_per_read = 256;            ///< bound on the drain per tick
};

struct UdpDeviceCounters {
    std::uint64_t received = 0;      ///< datagrams read
    std::uint64_t poses = 0;         ///< poses accepted
    std::uint64_t malformed = 0;     ///< dropped by the decoder (or wrong direction: force packets)
    std::uint64_t out_of_order = 0;  ///< dropped as late or duplicated
    std::uint64_t forces_sent = 0;
    std::uint64_t send_failures = 0;
    std::uint64_t driver_changes = 0;  ///< streams started by a new sender after the first
    bool bye = false;
    bool timed_out = false;
};

class UdpDevice final : public HapticDevice {
  public:
    explicit UdpDevice(UdpDeviceConfig config = {});

    /// Binds the socket; throws std::runtime_error when the port is taken.
    void open() override;
    ReadStatus read(DeviceState& state) override;
    void write_force(const ForceCommand& command) override;
    void close() override;
    double max_force() const override { return config_.max_force; }
    std::string name() const override;

    /// The bound port, valid after open() (from any thread).
    std::uint16_t port() const { return port_.load(); }
    /// Safe from any thread, including while the loop runs.
    UdpDeviceCounters counters() const;

  private:
    UdpDeviceConfig config_;
    std::optional<UdpSocket> socket_;
    std::atomic<std::uint16_t> port_{0};
    SequenceFilter filter_;
    DeviceState latest_;
    std::optional<UdpEndpoint> peer_;
    std::int64_t last_pose_ns_ = 0;
    std::uint32_t sequence_out_ = 0;
    std::atomic<std::uint64_t> received_{0}, poses_{0}, malformed_{0}, out_of_order_{0},
        forces_sent_{0}, send_failures_{0}, driver_changes_{0};
    std::atomic<bool> bye_{false}, timed_out_{false};
};

}  // namespace sandtin::haptics
