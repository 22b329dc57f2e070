#include "haptics/udp_protocol.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "geom/height_limit.hpp"

namespace sandtin::haptics {

namespace {

// Appends little-endian bytes to a fixed buffer (sizes are checked by the caller's layout).
struct Writer {
    std::span<std::uint8_t, kMaxPacketSize> out;
    std::size_t at = 0;
    void byte(std::uint8_t v) { out[at++] = v; }
    void u16(std::uint16_t v) {
        byte(static_cast<std::uint8_t>(v & 0xFFu));
        byte(static_cast<std::uint8_t>(v >> 8));
    }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            byte(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void f64(double v) {
        const auto bits = std::bit_cast<std::uint64_t>(v);
        for (int i = 0; i < 8; ++i)
            byte(static_cast<std::uint8_t>(bits >> (8 * i)));
    }
};
std::uint32_t get_u32(std::span<const std::uint8_t> b, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
        v = (v << 8) | b[at + static_cast<std::size_t>(i)];
    return v;
}
std::uint16_t get_u16(std::span<const std::uint8_t> b, std::size_t at) {
    return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
double get_f64(std::span<const std::uint8_t> b, std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i)
        v = (v << 8) | b[at + static_cast<std::size_t>(i)];
    return std::bit_cast<double>(v);
}
bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// A height the rest of the program accepts: beyond it a recording that kept the pose is
// refused by the loader (haptic_recording.cpp). x and y may be anything finite: a probe off the
// terrain touches nothing (force_model.hpp).
bool in_range(const Vec3& v) {
    return std::abs(v.z) <= kMaxHeight;
}
std::optional<Packet> failure(DecodeError e, DecodeError* out) {
    if (out != nullptr) *out = e;
    return std::nullopt;
}

}  // namespace

std::string_view to_string(DecodeError error) {
    switch (error) {
        case DecodeError::None:
            return "none";
        case DecodeError::TooShort:
            return "shorter than the 12-byte header";
        case DecodeError::BadMagic:
            return "bad magic (not 'SHAP')";
        case DecodeError::BadVersion:
            return "unsupported protocol version";
        case DecodeError::BadType:
            return "unknown packet type";
        case DecodeError::BadLength:
            return "length does not match the packet type";
        case DecodeError::NonFinite:
            return "non-finite number";
        case DecodeError::OutOfRange:
            return "pose height beyond 1e9 m";
    }
    return "unknown error";
}

std::size_t encode_packet(const Packet& packet, std::span<std::uint8_t, kMaxPacketSize> out) {
    Writer w{out};
    for (std::uint8_t m : kProtocolMagic)
        w.byte(m);
    w.byte(kProtocolVersion);
    w.byte(static_cast<std::uint8_t>(packet.type()));
    std::uint16_t length = 0;
    if (std::holds_alternative<PosePacket>(packet.body)) length = kPosePayloadSize;
    if (std::holds_alternative<ForcePacket>(packet.body)) length = kForcePayloadSize;
    w.u16(length);
    w.u32(packet.sequence);
    if (const auto* pose = std::get_if<PosePacket>(&packet.body)) {
        w.f64(pose->position.x);
        w.f64(pose->position.y);
        w.f64(pose->position.z);
        w.u32(pose->buttons);
    } else if (const auto* force = std::get_if<ForcePacket>(&packet.body)) {
        w.u32(force->ack);
        w.u32(force->flags);
        w.f64(force->force.x);
        w.f64(force->force.y);
        w.f64(force->force.z);
    }
    return w.at;
}

std::vector<std::uint8_t> encode_packet(const Packet& packet) {
    std::array<std::uint8_t, kMaxPacketSize> buffer{};
    const std::size_t n = encode_packet(packet, buffer);
    return {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n)};
}

std::optional<Packet> decode_packet(std::span<const std::uint8_t> b, DecodeError* error) {
    if (error != nullptr) *error = DecodeError::None;
    if (b.size() < kHeaderSize) return failure(DecodeError::TooShort, error);
    if (std::memcmp(b.data(), kProtocolMagic, 4) != 0) return failure(DecodeError::BadMagic, error);
    if (b[4] != kProtocolVersion) return failure(DecodeError::BadVersion, error);
    const std::uint8_t type = b[5];
    std::size_t expected = 0;
    switch (type) {
        case static_cast<std::uint8_t>(PacketType::Pose):
            expected = kPosePayloadSize;
            break;
        case static_cast<std::uint8_t>(PacketType::Force):
            expected = kForcePayloadSize;
            break;
        case static_cast<std::uint8_t>(PacketType::Bye):
            expected = 0;
            break;
        default:
            return failure(DecodeError::BadType, error);
    }
    const std::uint16_t length = get_u16(b, 6);
    if (length != expected || b.size() != kHeaderSize + expected)
        return failure(DecodeError::BadLength, error);
    Packet p;
    p.sequence = get_u32(b, 8);
    constexpr std::size_t h = kHeaderSize;
    if (type == static_cast<std::uint8_t>(PacketType::Pose)) {
        PosePacket pose;
        pose.position = {get_f64(b, h), get_f64(b, h + 8), get_f64(b, h + 16)};
        pose.buttons = get_u32(b, h + 24);
        if (!finite(pose.position)) return failure(DecodeError::NonFinite, error);
        if (!in_range(pose.position)) return failure(DecodeError::OutOfRange, error);
        p.body = pose;
    } else if (type == static_cast<std::uint8_t>(PacketType::Force)) {
        ForcePacket force;
        force.ack = get_u32(b, h);
        force.flags = get_u32(b, h + 4);
        force.force = {get_f64(b, h + 8), get_f64(b, h + 16), get_f64(b, h + 24)};
        if (!finite(force.force)) return failure(DecodeError::NonFinite, error);
        p.body = force;
    } else {
        p.body = ByePacket{};
    }
    return p;
}

}  // namespace sandtin::haptics
