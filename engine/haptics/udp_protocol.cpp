#include "haptics/udp_protocol.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace sandtin::haptics {

namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v & 0xFFu));
    out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_f64(std::vector<std::uint8_t>& out, double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int i = 0; i < 8; ++i)
        out.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
}
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
    }
    return "unknown error";
}

std::vector<std::uint8_t> encode_packet(const Packet& packet) {
    std::vector<std::uint8_t> out;
    out.reserve(kMaxPacketSize);
    out.insert(out.end(), std::begin(kProtocolMagic), std::end(kProtocolMagic));
    out.push_back(kProtocolVersion);
    out.push_back(static_cast<std::uint8_t>(packet.type()));
    std::uint16_t length = 0;
    if (std::holds_alternative<PosePacket>(packet.body)) length = kPosePayloadSize;
    if (std::holds_alternative<ForcePacket>(packet.body)) length = kForcePayloadSize;
    put_u16(out, length);
    put_u32(out, packet.sequence);
    if (const auto* pose = std::get_if<PosePacket>(&packet.body)) {
        put_f64(out, pose->position.x);
        put_f64(out, pose->position.y);
        put_f64(out, pose->position.z);
        put_u32(out, pose->buttons);
    } else if (const auto* force = std::get_if<ForcePacket>(&packet.body)) {
        put_u32(out, force->ack);
        put_u32(out, force->flags);
        put_f64(out, force->force.x);
        put_f64(out, force->force.y);
        put_f64(out, force->force.z);
    }
    return out;
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
