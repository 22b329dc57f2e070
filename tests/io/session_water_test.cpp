// Water in session files (io/session_file.hpp, chunk 'WAT1'): a wet terrain's water depths come
// back bit for bit, and a dry terrain's file holds no water chunk (so it is what an older build
// wrote); water kept by a build that did not know it, for a terrain that build rewrote, is
// dropped with a flag, while the same chunk over its own terrain is taken; a water chunk whose
// depths do not fit its terrain is refused with a message naming it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/session_file.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {
namespace session_water_test {

constexpr std::uint32_t kWaterTag = 'W' | ('A' << 8) | ('T' << 16) | (std::uint32_t{'1'} << 24);

Tin terrain(std::uint64_t seed) {
    return Tin::random_points(Rect::from_size(3.0, 2.0), 200, seed,
                              [](Vec2 p) { return 0.3 + 0.05 * std::sin(3.0 * p.x); });
}

Session session_of(const Tin& tin) {
    Session s;
    s.terrain = tin.snapshot();
    return s;
}

/// The body of the file's water chunk, or empty when it has none (chunks follow the 32-byte
/// header as {u32 tag, u64 length, body}).
std::vector<std::uint8_t> water_chunk(const std::vector<std::uint8_t>& file) {
    std::size_t at = 32;
    while (at + 12 <= file.size()) {
        std::uint32_t tag = 0;
        std::uint64_t length = 0;
        std::memcpy(&tag, file.data() + at, 4);
        std::memcpy(&length, file.data() + at + 4, 8);
        const auto* body = file.data() + at + 12;
        if (tag == kWaterTag) return {body, body + length};
        at += 12 + length;
    }
    return {};
}

TEST(SessionWater, AWetTerrainsWaterComesBackBitForBit) {
    Tin tin = terrain(1);
    std::size_t wet = 0;
    for (VertexId v : test::live_ids(tin)) {
        if (tin.position(v).x < 1.2) continue;
        tin.set_water_depth(v, 0.01 / 3.0 * tin.position(v).x);  // not a round binary number
        ++wet;
    }
    ASSERT_GT(wet, 0u);
    const std::vector<std::uint8_t> bytes = encode_session(session_of(tin));
    EXPECT_FALSE(water_chunk(bytes).empty());
    Session d = decode_session(bytes);
    EXPECT_FALSE(d.stale_water_dropped);
    EXPECT_EQ(d.terrain.vertices.water_depth, tin.vertices().water_depth);
    const Tin loaded = Tin::from_snapshot(std::move(d.terrain));
    EXPECT_EQ(loaded.vertices().water_depth, tin.vertices().water_depth);
    EXPECT_TRUE(loaded.check_valid().ok());
}

TEST(SessionWater, ADryTerrainsFileHoldsNoWaterChunk) {
    Tin tin = terrain(2);
    const std::vector<std::uint8_t> bytes = encode_session(session_of(tin));
    EXPECT_TRUE(water_chunk(bytes).empty());
    const Session d = decode_session(bytes);
    for (double depth : d.terrain.vertices.water_depth)
        EXPECT_EQ(depth, 0.0);
    // Water that dries off entirely leaves a file like one that never held any.
    const VertexId v = test::live_ids(tin).front();
    tin.set_water_depth(v, 0.02);
    tin.set_water_depth(v, 0.0);
    EXPECT_EQ(encode_session(session_of(tin)), bytes);
}

TEST(SessionWater, WaterKeptForAnotherVersionOfTheTerrainIsDropped) {
    Tin wet = terrain(3);
    for (VertexId v : test::live_ids(wet))
        wet.set_water_depth(v, 0.005);
    const std::vector<std::uint8_t> chunk = water_chunk(encode_session(session_of(wet)));
    ASSERT_FALSE(chunk.empty());

    // A build that did not know water kept the chunk verbatim and saved its own edit of the
    // terrain: that water no longer fits.
    Tin edited = terrain(3);
    edited.set_height(test::live_ids(edited).front(), 0.5);
    Session old_build = session_of(edited);
    old_build.unknown_chunks[kWaterTag] = chunk;
    const Session stale = decode_session(encode_session(old_build));
    EXPECT_TRUE(stale.stale_water_dropped);
    EXPECT_EQ(*std::max_element(stale.terrain.vertices.water_depth.begin(),
                                stale.terrain.vertices.water_depth.end()),
              0.0);
    EXPECT_TRUE(stale.unknown_chunks.empty());  // not carried on as an unknown chunk either

    // The same chunk over the terrain it was written for (the build saved without editing) is
    // that terrain's water.
    Tin unedited = terrain(3);
    Session kept = session_of(unedited);
    kept.unknown_chunks[kWaterTag] = chunk;
    const Session fresh = decode_session(encode_session(kept));
    EXPECT_FALSE(fresh.stale_water_dropped);
    EXPECT_EQ(fresh.terrain.vertices.water_depth, wet.vertices().water_depth);
}

TEST(SessionWater, DepthsThatDoNotFitTheirTerrainAreRefused) {
    Tin wet = terrain(4);
    for (VertexId v : test::live_ids(wet))
        wet.set_water_depth(v, 0.001);
    const std::vector<std::uint8_t> chunk = water_chunk(encode_session(session_of(wet)));
    ASSERT_GE(chunk.size(), 12u);
    const auto refused = [&](std::vector<std::uint8_t> body, const std::string& expected) {
        Session s = session_of(terrain(4));
        s.unknown_chunks[kWaterTag] = std::move(body);
        try {
            (void)decode_session(encode_session(s), "wet.sandtin");
            ADD_FAILURE() << expected << ": loaded";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("wet.sandtin"), std::string::npos) << e.what();
        }
    };
    // The right terrain checksum, three depths for a terrain of ~200 ids.
    std::vector<std::uint8_t> short_body(chunk.begin(), chunk.begin() + 4);
    const std::uint64_t three = 3;
    short_body.insert(short_body.end(), reinterpret_cast<const std::uint8_t*>(&three),
                      reinterpret_cast<const std::uint8_t*>(&three) + 8);
    short_body.resize(short_body.size() + 3 * sizeof(double), 0);
    refused(short_body, "water chunk holds 3 depths");
    // A negative depth.
    std::vector<std::uint8_t> negative = chunk;
    const double minus = -0.25;
    std::memcpy(negative.data() + 12, &minus, sizeof minus);
    refused(negative, "negative or non-finite water depth");
}

}  // namespace session_water_test
}  // namespace
}  // namespace sandtin
