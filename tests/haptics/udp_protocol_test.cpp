// The protocol codec: byte layout against a hand-assembled packet, round trips, and every way
// a datagram can be malformed.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

#include "geom/height_limit.hpp"
#include "haptics/sequence_filter.hpp"
#include "haptics/udp_protocol.hpp"

namespace sandtin::haptics {
namespace {

TEST(UdpProtocol, PoseLayoutIsLittleEndianAsDocumented) {
    const Packet p{0x01020304u, PosePacket{{1.0, -2.5, 0.125}, 0xA0B0C0D0u}};
    const std::vector<std::uint8_t> bytes = encode_packet(p);
    ASSERT_EQ(bytes.size(), 12u + 28u);
    const std::vector<std::uint8_t> header = {'S', 'H', 'A', 'P', 1, 1, 28, 0, 4, 3, 2, 1};
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 12), header);
    // 1.0 = 0x3FF0000000000000, least significant byte first.
    const std::vector<std::uint8_t> one = {0, 0, 0, 0, 0, 0, 0xF0, 0x3F};
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 12, bytes.begin() + 20), one);
    const std::vector<std::uint8_t> buttons = {0xD0, 0xC0, 0xB0, 0xA0};
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 36, bytes.end()), buttons);
}

TEST(UdpProtocol, RoundTripsEveryType) {
    const std::vector<Packet> packets = {
        {7, PosePacket{{0.25, 0.75, -0.001}, 1}},
        {8, ForcePacket{7, kForceFlagContact | kForceFlagStale, {0.1, -0.2, 9.75}}},
        {0xFFFFFFFFu, ByePacket{}},
    };
    for (const Packet& p : packets) {
        DecodeError e = DecodeError::BadMagic;
        const std::optional<Packet> q = decode_packet(encode_packet(p), &e);
        ASSERT_TRUE(q.has_value());
        EXPECT_EQ(e, DecodeError::None);
        EXPECT_EQ(*q, p);
    }
    EXPECT_EQ(encode_packet(packets[1]).size(), 44u);
    EXPECT_EQ(encode_packet(packets[2]).size(), 12u);
}

std::optional<Packet> decode_with(std::vector<std::uint8_t> b, DecodeError expected) {
    DecodeError e = DecodeError::None;
    std::optional<Packet> p = decode_packet(b, &e);
    EXPECT_EQ(e, expected) << to_string(e);
    return p;
}

TEST(UdpProtocol, MalformedPacketsAreRejectedWithTheReason) {
    const std::vector<std::uint8_t> good = encode_packet({1, PosePacket{{0.5, 0.5, 0.0}, 0}});
    EXPECT_FALSE(decode_with({}, DecodeError::TooShort));
    EXPECT_FALSE(decode_with({good.begin(), good.begin() + 11}, DecodeError::TooShort));
    auto b = good;
    b[0] = 'X';
    EXPECT_FALSE(decode_with(b, DecodeError::BadMagic));
    b = good;
    b[4] = 2;
    EXPECT_FALSE(decode_with(b, DecodeError::BadVersion));
    for (std::uint8_t t : {0, 4, 255}) {
        b = good;
        b[5] = t;
        EXPECT_FALSE(decode_with(b, DecodeError::BadType));
    }
    b = good;
    b[6] = 27;  // length field wrong for a pose
    EXPECT_FALSE(decode_with(b, DecodeError::BadLength));
    b = good;
    b.push_back(0);  // datagram longer than the length field
    EXPECT_FALSE(decode_with(b, DecodeError::BadLength));
    b = std::vector<std::uint8_t>(good.begin(), good.end() - 1);  // truncated payload
    EXPECT_FALSE(decode_with(b, DecodeError::BadLength));
    b = good;
    b[5] = 3;  // a bye with a pose's length
    EXPECT_FALSE(decode_with(b, DecodeError::BadLength));
    b = encode_packet({1, PosePacket{{0.5, std::numeric_limits<double>::quiet_NaN(), 0.0}, 0}});
    EXPECT_FALSE(decode_with(b, DecodeError::NonFinite));
    b = encode_packet({1, ForcePacket{1, 0, {std::numeric_limits<double>::infinity(), 0, 0}}});
    EXPECT_FALSE(decode_with(b, DecodeError::NonFinite));
    // The error argument is optional.
    EXPECT_FALSE(decode_packet(std::vector<std::uint8_t>{1, 2, 3}).has_value());
}

TEST(UdpProtocol, PosesBeyondTheLargestTerrainHeightAreMalformed) {
    // kMaxHeight (1e9 m) bounds every height a terrain, a script or a recording holds; a pose
    // beyond it would make the session's recording unreplayable.
    const double beyond = std::nextafter(kMaxHeight, 2.0 * kMaxHeight);
    for (const Vec3& p : {Vec3{0.5, 0.5, -2e9}, Vec3{1e300, 1e300, -1e300}, Vec3{0.5, 0.5, beyond},
                          Vec3{0.5, 0.5, -std::numeric_limits<double>::max()}}) {
        EXPECT_FALSE(decode_with(encode_packet({1, PosePacket{p, 1}}), DecodeError::OutOfRange))
            << p.x << " " << p.y << " " << p.z;
    }
    // The limit itself is accepted, as the recording loader accepts it; so is any finite x and y
    // (terrains may lie up to 1e12 m out, and a probe off the terrain touches nothing).
    for (const Vec3& p : {Vec3{kMaxHeight, -kMaxHeight, kMaxHeight}, Vec3{0.5, 0.5, -kMaxHeight},
                          Vec3{beyond, -beyond, 0.0}, Vec3{1e300, -1e300, 0.2}}) {
        const std::optional<Packet> q =
            decode_with(encode_packet({1, PosePacket{p, 0}}), DecodeError::None);
        ASSERT_TRUE(q.has_value());
        EXPECT_EQ(std::get<PosePacket>(q->body).position, p);
    }
    EXPECT_NE(to_string(DecodeError::OutOfRange), to_string(DecodeError::NonFinite));
}

TEST(UdpProtocol, EveryTruncationAndByteFlipIsHandled) {
    // No crash and a consistent verdict for every prefix and every single-byte corruption.
    const std::vector<std::uint8_t> good = encode_packet({42, ForcePacket{41, 1, {1.0, 2.0, 3.0}}});
    for (std::size_t n = 0; n < good.size(); ++n) {
        EXPECT_FALSE(decode_packet(std::span(good.data(), n)).has_value()) << n;
    }
    for (std::size_t i = 0; i < good.size(); ++i) {
        for (int bit = 0; bit < 8; ++bit) {
            auto b = good;
            b[i] = static_cast<std::uint8_t>(b[i] ^ (1u << bit));
            DecodeError e = DecodeError::None;
            const std::optional<Packet> p = decode_packet(b, &e);
            EXPECT_EQ(p.has_value(), e == DecodeError::None);
            if (i < 8) {
                EXPECT_FALSE(p.has_value()) << "header byte " << i;
            }
        }
    }
}

TEST(SequenceFilter, DropsLateAndDuplicatePacketsAcrossWraparound) {
    SequenceFilter f;
    EXPECT_TRUE(f.accept(10));
    EXPECT_TRUE(f.accept(12));
    EXPECT_FALSE(f.accept(11));  // late
    EXPECT_FALSE(f.accept(12));  // duplicate
    EXPECT_TRUE(f.accept(13));
    EXPECT_EQ(f.accepted(), 3u);
    EXPECT_EQ(f.dropped(), 2u);
    SequenceFilter w;
    EXPECT_TRUE(w.accept(0xFFFFFFFEu));
    EXPECT_TRUE(w.accept(0xFFFFFFFFu));
    EXPECT_TRUE(w.accept(0u));  // wrapped: newer
    EXPECT_TRUE(w.accept(1u));
    EXPECT_FALSE(w.accept(0xFFFFFFFFu));  // older than 1 in serial arithmetic
}

}  // namespace
}  // namespace sandtin::haptics
