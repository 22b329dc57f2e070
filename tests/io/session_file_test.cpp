// Session files: round trips, and every kind of damage rejected with a clear message.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "support/scratch_folder.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kHeaderSize =
    32;  // magic 8, version 4, reserved 4, length 8, crc 4, reserved 4

double swell(Vec2 p) {
    return 0.5 + 0.1 * std::sin(p.x) * std::cos(p.y);
}

class SessionFile : public test::ScratchFolderTest {
  protected:
    SessionFile() : ScratchFolderTest("io") {}

    static Session make_session(std::size_t points = 300, std::uint64_t seed = 1) {
        Tin tin = Tin::random_points(Rect::from_size(6.0, 4.0), points, seed, swell);
        const VertexId a = tin.insert_point({1.0, 1.0}, 1.0);
        const VertexId b = tin.insert_point({5.0, 3.0}, 1.0);
        const VertexId c = tin.insert_point({1.0, 3.0}, 0.0);
        const VertexId d = tin.insert_point({5.0, 1.0}, 2.0);
        tin.insert_constraint(a, b, 3);
        tin.insert_constraint(c, d, 4);  // crosses a-b
        for (VertexId v : test::live_ids(tin)) {
            if (v.value % 13 == 0 && !tin.is_boundary(v) && !tin.is_on_constraint(v))
                tin.remove_vertex(v);
            if (tin.is_alive(v) && v.value % 5 == 0) tin.set_moisture(v, 0.5f);
        }
        Session s;
        s.terrain = tin.snapshot();
        s.next_generation = 5;
        s.metadata_json = R"({"name":"test scene","tool":{"radius":0.25}})";
        return s;
    }

    fs::path path(const std::string& name) const { return dir_ / name; }

    static void write_bytes(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
        std::ofstream out(p, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }

    /// Expects load_session(p) to throw std::runtime_error whose message contains one of the
    /// keywords.
    static void expect_load_error(const fs::path& p, const std::vector<std::string>& keywords,
                                  const std::string& what) {
        try {
            (void)load_session(p);
            ADD_FAILURE() << what << ": loaded without error";
        } catch (const std::runtime_error& e) {
            const std::string msg = e.what();
            bool found = false;
            for (const std::string& k : keywords)
                found = found || msg.find(k) != std::string::npos;
            EXPECT_TRUE(found) << what << ": message lacks the expected keyword: " << msg;
        } catch (const std::exception& e) {
            ADD_FAILURE() << what << ": wrong exception type: " << e.what();
        }
    }
};

/// Sets the payload CRC and the header CRC to match the (modified) file, as a crafted file
/// would.
void fix_crc(std::vector<std::uint8_t>& bytes) {
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), bytes.data() + kHeaderSize,
                            static_cast<uInt>(bytes.size() - kHeaderSize));
    const auto c = static_cast<std::uint32_t>(crc);
    std::memcpy(bytes.data() + 24, &c, 4);
    const auto h = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data(), 28));
    std::memcpy(bytes.data() + 28, &h, 4);
}

void set_payload_length(std::vector<std::uint8_t>& bytes) {
    const std::uint64_t n = bytes.size() - kHeaderSize;
    std::memcpy(bytes.data() + 16, &n, 8);
}

void expect_sessions_equal(const Session& a, const Session& b) {
    test::expect_snapshots_equal(a.terrain, b.terrain, 1.0);  // lumped_area is not stored
    EXPECT_EQ(a.next_generation, b.next_generation);
    EXPECT_EQ(a.metadata_json, b.metadata_json);
    EXPECT_EQ(a.unknown_chunks, b.unknown_chunks);
}

TEST_F(SessionFile, EncodeDecodeRoundTrip) {
    const Session s = make_session();
    const std::vector<std::uint8_t> bytes = encode_session(s);
    ASSERT_GT(bytes.size(), kHeaderSize);
    EXPECT_EQ(std::memcmp(bytes.data(), "SANDTIN\x1a", 8), 0);
    std::uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    EXPECT_EQ(version, kSessionFormatVersion);
    const Session d = decode_session(bytes);
    expect_sessions_equal(s, d);
    // Re-encoding the decoded session gives the same bytes.
    EXPECT_EQ(encode_session(d), bytes);
}

TEST_F(SessionFile, SaveLoadRestoresTheSameTin) {
    const Session s = make_session();
    save_session(path("scene.sandtin"), s);
    const Session loaded = load_session(path("scene.sandtin"));
    expect_sessions_equal(s, loaded);
    const Tin original = Tin::from_snapshot(s.terrain);
    const Tin restored = Tin::from_snapshot(loaded.terrain);
    test::expect_snapshots_equal(original.snapshot(), restored.snapshot());
    EXPECT_TRUE(restored.check_valid().ok());
    EXPECT_EQ(restored.constraint_count(), 2u);
    EXPECT_EQ(restored.volume(), original.volume());
}

TEST_F(SessionFile, SavedTerrainWithNeighbouringConstraintsLoads) {
    // A valid terrain whose forced (non-Delaunay) constrained edge faces the end vertex of an
    // older constraint: what is saved must load.
    Tin tin = Tin::flat_rectangle(Rect::from_size(10.0, 10.0), 1.0);
    const VertexId v = tin.insert_point({5.0, 5.5}, 1.0);
    tin.insert_point({5.0, 4.5}, 1.0);
    const VertexId u = tin.insert_point({5.0, 8.0}, 1.0);
    const VertexId b1 = tin.insert_point({2.0, 5.0}, 1.0);
    const VertexId b2 = tin.insert_point({8.0, 5.0}, 1.0);
    tin.insert_constraint(v, u, 1);
    tin.insert_constraint(b1, b2, 2);
    ASSERT_TRUE(tin.check_valid().ok());
    Session s;
    s.terrain = tin.snapshot();
    save_session(path("constrained.sandtin"), s);
    const Session loaded = load_session(path("constrained.sandtin"));
    try {
        const Tin restored = Tin::from_snapshot(loaded.terrain);
        EXPECT_TRUE(restored.is_constrained_edge(b1, b2));
        EXPECT_TRUE(restored.is_constrained_edge(v, u));
    } catch (const std::exception& e) {
        ADD_FAILURE() << "a saved valid terrain does not load: " << e.what();
    }
}

TEST_F(SessionFile, UnknownChunksSurviveARoundTrip) {
    Session s = make_session(50);
    s.unknown_chunks[0x31545845u] = {1, 2, 3, 4, 5};  // 'EXT1'
    s.unknown_chunks[0x32545845u] = {};               // empty body
    std::vector<std::uint8_t> big(70000);
    for (std::size_t i = 0; i < big.size(); ++i)
        big[i] = static_cast<std::uint8_t>(i * 7);
    s.unknown_chunks[0x7A7A7A7Au] = big;
    save_session(path("ext.sandtin"), s);
    const Session loaded = load_session(path("ext.sandtin"));
    EXPECT_EQ(loaded.unknown_chunks, s.unknown_chunks);
    save_session(path("ext2.sandtin"), loaded);
    EXPECT_EQ(read_file(path("ext2.sandtin")), read_file(path("ext.sandtin")));
}

TEST_F(SessionFile, EmptyMetadataAndDefaultGeneration) {
    Session s;
    s.terrain = Tin::flat_rectangle(Rect::from_size(1.0, 1.0)).snapshot();
    s.metadata_json.clear();
    const Session d = decode_session(encode_session(s));
    expect_sessions_equal(s, d);
    EXPECT_EQ(d.next_generation, 1u);
}

TEST_F(SessionFile, MissingFile) {
    expect_load_error(path("nope.sandtin"), {"no such file", "cannot"}, "missing file");
    expect_load_error(dir_, {"it is a folder, not a file"}, "a directory");
}

TEST_F(SessionFile, EmptyFile) {
    write_bytes(path("empty.sandtin"), {});
    // Empty, or cut short inside the magic: truncated, not "not a session".
    expect_load_error(path("empty.sandtin"), {"truncated: 0 bytes"}, "empty file");
    expect_load_error(path("empty.sandtin"), {"(the file is empty)"}, "empty file");
    const std::vector<std::uint8_t> whole = encode_session(make_session(20));
    write_bytes(path("cut.sandtin"), {whole.begin(), whole.begin() + 5});
    expect_load_error(path("cut.sandtin"), {"truncated: 5 bytes"}, "a 5-byte prefix");
}

TEST_F(SessionFile, TruncatedFiles) {
    const std::vector<std::uint8_t> bytes = encode_session(make_session());
    const std::size_t n = bytes.size();
    for (std::size_t cut :
         {std::size_t{9}, std::size_t{12}, std::size_t{20}, kHeaderSize - 1, kHeaderSize,
          kHeaderSize + 1, kHeaderSize + 13, n / 3, n / 2, n - 100, n - 1}) {
        const std::vector<std::uint8_t> part(bytes.begin(),
                                             bytes.begin() + static_cast<std::ptrdiff_t>(cut));
        write_bytes(path("cut.sandtin"), part);
        expect_load_error(path("cut.sandtin"), {"truncated"}, "cut at " + std::to_string(cut));
    }
    // Cut inside the magic: may be reported either way, but must be an error.
    for (std::size_t cut : {std::size_t{1}, std::size_t{4}, std::size_t{7}}) {
        write_bytes(path("cut.sandtin"),
                    std::vector<std::uint8_t>(bytes.begin(),
                                              bytes.begin() + static_cast<std::ptrdiff_t>(cut)));
        expect_load_error(path("cut.sandtin"), {"truncated", "not a sandtin"},
                          "cut at " + std::to_string(cut));
    }
}

TEST_F(SessionFile, FlippedPayloadBytesFailTheChecksum) {
    const std::vector<std::uint8_t> bytes = encode_session(make_session());
    for (std::size_t at :
         {kHeaderSize, kHeaderSize + 1, kHeaderSize + 40, bytes.size() / 2, bytes.size() - 1}) {
        std::vector<std::uint8_t> bad = bytes;
        bad[at] ^= 0x10;
        write_bytes(path("flip.sandtin"), bad);
        expect_load_error(path("flip.sandtin"), {"checksum"}, "flip at " + std::to_string(at));
    }
    std::vector<std::uint8_t> bad = bytes;
    bad[26] ^= 0x01;  // the stored CRC itself
    write_bytes(path("flip.sandtin"), bad);
    expect_load_error(path("flip.sandtin"), {"checksum"}, "flipped CRC");
}

TEST_F(SessionFile, FutureVersion) {
    std::vector<std::uint8_t> bytes = encode_session(make_session(20));
    const std::uint32_t future = kSessionFormatVersion + 1;
    std::memcpy(bytes.data() + 8, &future, 4);
    write_bytes(path("future.sandtin"), bytes);
    expect_load_error(path("future.sandtin"), {"newer"}, "future version");
}

TEST_F(SessionFile, BadMagic) {
    std::vector<std::uint8_t> bytes = encode_session(make_session(20));
    bytes[0] = 'X';
    write_bytes(path("magic.sandtin"), bytes);
    expect_load_error(path("magic.sandtin"), {"not a sandtin"}, "bad magic");
    const std::string text =
        "solid cube\nfacet normal 0 0 1\n this is some other file format entirely";
    write_bytes(path("garbage.sandtin"), std::vector<std::uint8_t>(text.begin(), text.end()));
    expect_load_error(path("garbage.sandtin"), {"not a sandtin"}, "garbage");
}

TEST_F(SessionFile, TrailingBytes) {
    std::vector<std::uint8_t> bytes = encode_session(make_session(20));
    const std::size_t end = bytes.size();
    bytes.push_back(0);
    write_bytes(path("trailing.sandtin"), bytes);
    // Named where they start: the end of the session's own bytes.
    expect_load_error(path("trailing.sandtin"), {"trailing"}, "trailing bytes");
    expect_load_error(path("trailing.sandtin"), {"(at byte " + std::to_string(end) + ")"},
                      "trailing bytes' offset");
}

TEST_F(SessionFile, AnInvalidTerrainInAnIntactFileNamesTheFile) {
    // Bytes and checksums intact, the triangulation not: a triangle names a vertex id past the
    // vertex table. The terrain is refused, and the message says which file it came from.
    Session s = make_session(20);
    ASSERT_FALSE(s.terrain.slots.empty());
    s.terrain.slots.front()[0] = 1000000;
    save_session(path("bad-topology.sandtin"), s);
    Session loaded = load_session(path("bad-topology.sandtin"));
    try {
        (void)take_session_terrain(loaded, path("bad-topology.sandtin"));
        ADD_FAILURE() << "an invalid triangulation was accepted";
    } catch (const std::exception& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("'" + path("bad-topology.sandtin").string() + "': ", 0), 0u) << m;
    }
    // An intact one loads the same as Tin::from_snapshot, and leaves the session's terrain empty
    // (moved into the TIN) and the rest of the session as it was.
    Session good = make_session(20);
    const Session copy = good;
    EXPECT_EQ(take_session_terrain(good, "x").vertex_count(),
              Tin::from_snapshot(copy.terrain).vertex_count());
    EXPECT_EQ(good.terrain.vertices.size(), 0u);
    EXPECT_EQ(good.metadata_json, copy.metadata_json);
    EXPECT_EQ(good.next_generation, copy.next_generation);
}

TEST_F(SessionFile, CraftedFilesWithValidChecksum) {
    const std::vector<std::uint8_t> good = encode_session(make_session(20));
    // A chunk claiming more bytes than the payload has.
    {
        std::vector<std::uint8_t> b = good;
        const std::uint64_t huge = 1ull << 40;
        std::memcpy(b.data() + kHeaderSize + 4, &huge, 8);
        fix_crc(b);
        write_bytes(path("c1.sandtin"), b);
        expect_load_error(path("c1.sandtin"), {"truncated"}, "oversized chunk");
    }
    // The first array inside the terrain chunk claims 2^40 items: must fail cleanly, not
    // allocate.
    {
        std::vector<std::uint8_t> b = good;
        const std::uint64_t huge = 1ull << 40;
        std::memcpy(b.data() + kHeaderSize + 12 + 32, &huge, 8);
        fix_crc(b);
        write_bytes(path("c2.sandtin"), b);
        expect_load_error(path("c2.sandtin"), {"truncated", "too long"}, "oversized array");
    }
    // No terrain chunk at all: only an unknown chunk.
    {
        std::vector<std::uint8_t> b(good.begin(), good.begin() + kHeaderSize);
        const std::uint32_t tag = 0x58585858u;
        const std::uint64_t len = 3;
        b.insert(b.end(), reinterpret_cast<const std::uint8_t*>(&tag),
                 reinterpret_cast<const std::uint8_t*>(&tag) + 4);
        b.insert(b.end(), reinterpret_cast<const std::uint8_t*>(&len),
                 reinterpret_cast<const std::uint8_t*>(&len) + 8);
        b.insert(b.end(), {1, 2, 3});
        set_payload_length(b);
        fix_crc(b);
        write_bytes(path("c3.sandtin"), b);
        expect_load_error(path("c3.sandtin"), {"no terrain"}, "no terrain chunk");
    }
    // A payload cut at a chunk boundary but with matching length and CRC.
    {
        std::vector<std::uint8_t> b(good.begin(), good.begin() + kHeaderSize + 12 + 20);
        std::uint64_t len = 20;
        std::memcpy(b.data() + kHeaderSize + 4, &len, 8);
        set_payload_length(b);
        fix_crc(b);
        write_bytes(path("c4.sandtin"), b);
        expect_load_error(path("c4.sandtin"), {"truncated"}, "terrain chunk too short");
    }
}

TEST_F(SessionFile, StructurallyInvalidTerrainIsRejectedOnLoad) {
    // Well-formed file, valid checksum, but the triangles name a dead vertex: loading it into
    // a Tin must fail with std::runtime_error.
    Session s = make_session(30);
    for (auto& c : s.terrain.slots) {
        if (c[0] != kNoSlot && c[0] < kOutsideCorner) {
            c[0] = static_cast<std::uint32_t>(s.terrain.vertices.size() + 1);
            break;
        }
    }
    save_session(path("bad.sandtin"), s);
    bool threw = false;
    try {
        const Session loaded = load_session(path("bad.sandtin"));
        (void)Tin::from_snapshot(loaded.terrain);
    } catch (const std::runtime_error& e) {
        threw = true;
        EXPECT_NE(std::string(e.what()).find("invalid"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(threw);
}

TEST_F(SessionFile, InterruptedSaveLeavesThePreviousFileIntact) {
    // Big enough (> 1 MiB) that the writer calls the hook after a partial write.
    const Session first = make_session(40000, 7);
    const Session second = make_session(40000, 8);
    const fs::path p = path("scene.sandtin");
    save_session(p, first);
    const std::vector<std::uint8_t> first_bytes = read_file(p);
    ASSERT_GT(first_bytes.size(), std::size_t{1} << 20);
    std::vector<std::size_t> calls;
    EXPECT_THROW(save_session(p, second,
                              [&](std::size_t written) {
                                  calls.push_back(written);
                                  return false;
                              }),
                 std::runtime_error);
    ASSERT_EQ(calls.size(), 1u);
    EXPECT_LT(calls[0], encode_session(second).size()) << "the hook should see a partial write";
    EXPECT_EQ(read_file(p), first_bytes);
    expect_sessions_equal(load_session(p), first);
    // Interrupting later (after the second chunk) also leaves the old file.
    EXPECT_THROW(save_session(p, second,
                              [](std::size_t written) { return written < (std::size_t{1} << 21); }),
                 std::runtime_error);
    EXPECT_EQ(read_file(p), first_bytes);
    // A hook that lets the save finish: the new file replaces the old one.
    std::size_t last = 0;
    save_session(p, second, [&](std::size_t written) {
        EXPECT_GT(written, last);
        last = written;
        return true;
    });
    EXPECT_EQ(last, encode_session(second).size());
    expect_sessions_equal(load_session(p), second);
}

}  // namespace
}  // namespace sandtin

// ---- Format versions, header damage, a save killed mid-write ---------------------------------

namespace sandtin {
namespace {

/// Written by the format-1 build (commit b3f3abe): `sandtin run` of a 40-point terrain with
/// one circular stamp, so it holds constraints.
const std::filesystem::path kVersion1File =
    std::filesystem::path(SANDTIN_TEST_DATA_DIR) / "session_v1.sandtin";

TEST_F(SessionFile, OlderFormatVersionLoads) {
    const std::vector<std::uint8_t> bytes = read_file(kVersion1File);
    std::uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    ASSERT_EQ(version, 1u) << "the fixture must stay a format-1 file";
    const Session s = load_session(kVersion1File);
    EXPECT_EQ(s.format_version, 1u);
    const Tin tin = Tin::from_snapshot(s.terrain);
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
    // What `sandtin info` reported for the file when the format-1 build wrote it.
    EXPECT_EQ(tin.vertex_count(), 60u);
    EXPECT_EQ(tin.triangle_count(), 114u);
    EXPECT_EQ(tin.constrained_edge_count(), 16u);
    EXPECT_EQ(tin.constraint_count(), 16u);
    EXPECT_NEAR(tin.volume(), 0.19673113906194895, 1e-15);
    // Saving upgrades it to the current format, with the same content.
    save_session(path("upgraded.sandtin"), s);
    const Session upgraded = load_session(path("upgraded.sandtin"));
    EXPECT_EQ(upgraded.format_version, kSessionFormatVersion);
    expect_sessions_equal(upgraded, s);
}

TEST_F(SessionFile, DamagedHeaderFieldsAreCaughtByTheHeaderChecksum) {
    const std::vector<std::uint8_t> good = encode_session(make_session(30));
    // Payload length, reserved word, payload CRC: each flip is corruption, not truncation.
    for (std::size_t at : {std::size_t{12}, std::size_t{16}, std::size_t{17}, std::size_t{23},
                           std::size_t{25}, std::size_t{29}}) {
        std::vector<std::uint8_t> bad = good;
        bad[at] ^= 0x04;
        write_bytes(path("h.sandtin"), bad);
        expect_load_error(path("h.sandtin"), {"header checksum"}, "flip at " + std::to_string(at));
    }
    std::vector<std::uint8_t> zero = good;
    std::memset(zero.data() + 8, 0, 4);
    write_bytes(path("z.sandtin"), zero);
    expect_load_error(path("z.sandtin"), {"corrupted"}, "format version 0");
    std::vector<std::uint8_t> huge = good;
    const std::uint32_t v = 0xFFFFFFFFu;
    std::memcpy(huge.data() + 8, &v, 4);
    write_bytes(path("v.sandtin"), huge);
    expect_load_error(path("v.sandtin"), {"newer"}, "future version 2^32-1");
}

TEST_F(SessionFile, SaveKilledMidWriteLeavesTheOldFileLoadable) {
    // A real crash: a child process starts saving over the file and is killed with SIGKILL
    // from inside the write (after a partial write, via the interruption hook).
    const Session old_session = make_session(40000, 3);
    const Session new_session = make_session(40000, 4);
    const fs::path p = path("scene.sandtin");
    save_session(p, old_session);
    const std::vector<std::uint8_t> before = read_file(p);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        try {
            save_session(p, new_session, [](std::size_t written) {
                if (written > 0) ::kill(::getpid(), SIGKILL);
                return true;
            });
        } catch (...) {
        }
        ::_exit(0);  // not reached: the kill comes first
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the child should have died mid-save";
    EXPECT_EQ(WTERMSIG(status), SIGKILL);
    EXPECT_EQ(read_file(p), before);
    expect_sessions_equal(load_session(p), old_session);
    // The killed save's temporary is left behind; it never shadows the scene.
    std::size_t temporaries = 0;
    for (const auto& e : fs::directory_iterator(dir_))
        temporaries += e.path().filename().string().find(".tmp-") != std::string::npos ? 1 : 0;
    EXPECT_EQ(temporaries, 1u);
}

}  // namespace
}  // namespace sandtin
