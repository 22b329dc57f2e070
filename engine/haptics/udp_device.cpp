#include "haptics/udp_device.hpp"

#include <array>
#include <chrono>
#include <stdexcept>

#include "haptics/udp_protocol.hpp"

namespace sandtin::haptics {

namespace {
std::int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}
}  // namespace

UdpDevice::UdpDevice(UdpDeviceConfig config) : config_(config) {
    if (!(config_.max_force > 0.0))
        throw std::invalid_argument("udp device: max_force must be > 0");
    if (config_.loss_timeout_ns <= 0)
        throw std::invalid_argument("udp device: loss_timeout_ns must be > 0");
    if (config_.max_datagrams_per_read < 1)
        throw std::invalid_argument("udp device: max_datagrams_per_read must be >= 1");
}

std::string UdpDevice::name() const {
    return "udp:" + std::to_string(port());
}

void UdpDevice::open() {
    if (socket_) throw std::runtime_error("udp device: already open");
    socket_ = UdpSocket::bind(config_.port, config_.address);
    port_.store(socket_->port());
    filter_.reset();
    latest_ = {};
    peer_.reset();
    bye_.store(false);
    timed_out_.store(false);
}

void UdpDevice::close() {
    socket_.reset();
}

UdpDeviceCounters UdpDevice::counters() const {
    UdpDeviceCounters c;
    c.received = received_.load(std::memory_order_relaxed);
    c.poses = poses_.load(std::memory_order_relaxed);
    c.malformed = malformed_.load(std::memory_order_relaxed);
    c.out_of_order = out_of_order_.load(std::memory_order_relaxed);
    c.forces_sent = forces_sent_.load(std::memory_order_relaxed);
    c.send_failures = send_failures_.load(std::memory_order_relaxed);
    c.driver_changes = driver_changes_.load(std::memory_order_relaxed);
    c.bye = bye_.load(std::memory_order_relaxed);
    c.timed_out = timed_out_.load(std::memory_order_relaxed);
    return c;
}

ReadStatus UdpDevice::read(DeviceState& state) {
    if (!socket_) return ReadStatus::Lost;
    std::array<std::uint8_t, kMaxPacketSize> buffer{};
    for (int i = 0; i < config_.max_datagrams_per_read; ++i) {
        UdpEndpoint from;
        const std::optional<std::size_t> n = socket_->receive(buffer, &from);
        if (!n) break;
        received_.fetch_add(1, std::memory_order_relaxed);
        if (*n > buffer.size()) {  // oversized: never a valid packet
            malformed_.fetch_add(1, std::memory_order_relaxed);
            continue;
        }
        const std::optional<Packet> p =
            decode_packet(std::span<const std::uint8_t>(buffer.data(), *n));
        if (!p || p->type() == PacketType::Force) {
            malformed_.fetch_add(1, std::memory_order_relaxed);
            continue;
        }
        if (peer_ && from != *peer_) {
            filter_.reset();  // a new driver: its own sequence numbers
            peer_ = from;
            driver_changes_.fetch_add(1, std::memory_order_relaxed);
        }
        if (!filter_.accept(p->sequence)) {
            out_of_order_.fetch_add(1, std::memory_order_relaxed);
            continue;
        }
        if (p->type() == PacketType::Bye) {
            bye_.store(true, std::memory_order_relaxed);
            return ReadStatus::Lost;
        }
        const auto& pose = std::get<PosePacket>(p->body);
        latest_.position = pose.position;
        latest_.buttons = pose.buttons;
        latest_.sequence = p->sequence;
        latest_.valid = true;
        peer_ = from;
        last_pose_ns_ = now_ns();
        poses_.fetch_add(1, std::memory_order_relaxed);
    }
    if (latest_.valid && now_ns() - last_pose_ns_ > config_.loss_timeout_ns) {
        timed_out_.store(true, std::memory_order_relaxed);
        return ReadStatus::Lost;
    }
    state = latest_;
    return ReadStatus::Ok;
}

void UdpDevice::write_force(const ForceCommand& command) {
    if (!socket_ || !peer_ || !latest_.valid) return;
    ForcePacket f;
    f.ack = latest_.sequence;
    f.flags = (command.contact ? kForceFlagContact : 0u) | (command.stale ? kForceFlagStale : 0u);
    f.force = command.force;
    std::array<std::uint8_t, kMaxPacketSize> bytes{};
    const std::size_t n = encode_packet({++sequence_out_, f}, bytes);
    if (socket_->send_to(std::span<const std::uint8_t>(bytes.data(), n), *peer_)) {
        forces_sent_.fetch_add(1, std::memory_order_relaxed);
    } else {
        send_failures_.fetch_add(1, std::memory_order_relaxed);
    }
}

}  // namespace sandtin::haptics
