#pragma once
// The sandtin haptic UDP protocol, version 1: a separate driver process owns the hardware and
// exchanges small datagrams with sandtin on loopback. Pure encode/decode, no sockets, so the
// decoder can be fuzzed on its own.
//
// Every datagram is one packet, all fields little-endian, doubles IEEE-754 binary64:
//
//   offset size  field
//        0    4  magic "SHAP" (bytes 0x53 0x48 0x41 0x50)
//        4    1  version = 1
//        5    1  type: 1 pose (driver -> sandtin), 2 force (sandtin -> driver),
//                      3 bye (driver -> sandtin: the stream ends, stop the loop)
//        6    2  payload length in bytes: must equal the type's size below
//        8    4  sequence: per sender, +1 per packet (wraps at 2^32; order is judged by serial
//                number arithmetic, see SequenceFilter)
//       12       payload
//
//   pose  (28 bytes): f64 x, f64 y, f64 z   device point in the terrain frame (m)
//                     u32 buttons            bit 0 = the stylus button
//   force (32 bytes): u32 ack               sequence of the latest pose the force answers
//                     u32 flags             bit 0 = contact, bit 1 = stale snapshot (ramping)
//                     f64 fx, f64 fy, f64 fz (N)
//   bye   (0 bytes)
//
// A packet is malformed, and dropped, when it is shorter than the header, has another magic,
// version or type, a length field that is not the type's size or does not match the datagram,
// a non-finite number, or a pose height beyond kMaxHeight (geom/height_limit.hpp: 1e9 m, the
// largest height a terrain, a script or a recording may hold; a session that recorded such a
// pose could not be replayed). The receiver also drops packets whose sequence is not newer than
// the last accepted one (late or duplicated datagrams); both are counted, neither stops the
// loop.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "geom/vec3.hpp"

namespace sandtin::haptics {

inline constexpr std::uint8_t kProtocolMagic[4] = {0x53, 0x48, 0x41, 0x50};  // "SHAP"
inline constexpr std::uint8_t kProtocolVersion = 1;
inline constexpr std::size_t kHeaderSize = 12;
inline constexpr std::size_t kPosePayloadSize = 28;
inline constexpr std::size_t kForcePayloadSize = 32;
/// The largest packet; receivers use a buffer at least this big (bigger datagrams are
/// malformed).
inline constexpr std::size_t kMaxPacketSize = kHeaderSize + kForcePayloadSize;

enum class PacketType : std::uint8_t { Pose = 1, Force = 2, Bye = 3 };

inline constexpr std::uint32_t kForceFlagContact = 1u;
inline constexpr std::uint32_t kForceFlagStale = 2u;

struct PosePacket {
    Vec3 position;  ///< m
    std::uint32_t buttons = 0;
    friend bool operator==(const PosePacket&, const PosePacket&) = default;
};
struct ForcePacket {
    std::uint32_t ack = 0;
    std::uint32_t flags = 0;
    Vec3 force;  ///< N
    friend bool operator==(const ForcePacket&, const ForcePacket&) = default;
};
struct ByePacket {
    friend bool operator==(const ByePacket&, const ByePacket&) = default;
};

struct Packet {
    std::uint32_t sequence = 0;
    std::variant<PosePacket, ForcePacket, ByePacket> body;
    PacketType type() const { return static_cast<PacketType>(body.index() + 1); }
    friend bool operator==(const Packet&, const Packet&) = default;
};

enum class DecodeError : std::uint8_t {
    None,
    TooShort,  ///< fewer bytes than the header
    BadMagic,
    BadVersion,
    BadType,
    BadLength,   ///< length field wrong for the type, or not the datagram's size
    NonFinite,   ///< a NaN or infinite coordinate or force
    OutOfRange,  ///< a pose height (z) whose magnitude exceeds kMaxHeight (1e9 m)
};
std::string_view to_string(DecodeError error);

/// Encodes a packet (header + payload), little-endian whatever the host order.
std::vector<std::uint8_t> encode_packet(const Packet& packet);
/// The same into a caller's buffer, without allocating (the force loop's path); returns the
/// packet's size.
std::size_t encode_packet(const Packet& packet, std::span<std::uint8_t, kMaxPacketSize> out);
/// Decodes one datagram. On failure returns nullopt and, when `error` is given, sets it.
std::optional<Packet> decode_packet(std::span<const std::uint8_t> bytes,
                                    DecodeError* error = nullptr);

}  // namespace sandtin::haptics
