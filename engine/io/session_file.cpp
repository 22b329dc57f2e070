#include "io/session_file.hpp"

#include <zlib.h>

#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "io/byte_stream.hpp"

namespace sandtin {

namespace {

constexpr std::array<std::uint8_t, 8> kMagic = {'S', 'A', 'N', 'D', 'T', 'I', 'N', 0x1a};
constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 4 + 4;
constexpr std::size_t kHeaderChecked = kHeaderSize - 4;  ///< bytes the header CRC covers

constexpr std::uint32_t tag(char a, char b, char c, char d) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(a)) |
           (static_cast<std::uint32_t>(static_cast<unsigned char>(b)) << 8) |
           (static_cast<std::uint32_t>(static_cast<unsigned char>(c)) << 16) |
           (static_cast<std::uint32_t>(static_cast<unsigned char>(d)) << 24);
}
constexpr std::uint32_t kTagTin = tag('T', 'I', 'N', '1');
constexpr std::uint32_t kTagMeta = tag('M', 'E', 'T', 'A');
constexpr std::uint32_t kTagGeneration = tag('G', 'E', 'N', '1');
constexpr std::uint32_t kTagWater = tag('W', 'A', 'T', '1');

std::uint32_t crc32_of(std::span<const std::uint8_t> bytes) {
    uLong crc = crc32(0L, Z_NULL, 0);
    std::size_t offset = 0;
    while (offset < bytes.size()) {
        const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size() - offset, 1u << 30));
        crc = crc32(crc, bytes.data() + offset, n);
        offset += n;
    }
    return static_cast<std::uint32_t>(crc);
}

void encode_terrain(ByteWriter& w, const TinSnapshot& t) {
    w.put(t.domain.min.x);
    w.put(t.domain.min.y);
    w.put(t.domain.max.x);
    w.put(t.domain.max.y);
    const VertexArrays& v = t.vertices;
    w.put_array<Vec2>(v.position);
    w.put_array<double>(v.height);
    w.put_array<double>(v.bedrock);
    w.put_array<std::uint16_t>(v.material);
    w.put_array<float>(v.moisture);
    w.put_array<Vec2f>(v.slide);
    w.put_array<std::uint8_t>(v.alive);
    w.put_array<std::uint32_t>(t.vertex_free_list);
    w.put_array<std::array<std::uint32_t, 3>>(t.slots);
    w.put_array<std::uint32_t>(t.slot_free_list);
    w.put<std::uint32_t>(t.constraint_capacity);
    w.put<std::uint64_t>(t.constraints.size());
    for (const ConstraintRecord& c : t.constraints) {
        w.put(c.id);
        w.put(c.generation);
        w.put_array<std::uint32_t>(c.vertices);
    }
    w.put_array<std::uint32_t>(t.constraint_free_list);
}

TinSnapshot decode_terrain(ByteReader& r) {
    TinSnapshot t;
    t.domain.min.x = r.get<double>();
    t.domain.min.y = r.get<double>();
    t.domain.max.x = r.get<double>();
    t.domain.max.y = r.get<double>();
    VertexArrays& v = t.vertices;
    v.position = r.get_array<Vec2>();
    v.height = r.get_array<double>();
    v.bedrock = r.get_array<double>();
    v.material = r.get_array<std::uint16_t>();
    v.moisture = r.get_array<float>();
    v.slide = r.get_array<Vec2f>();
    v.alive = r.get_array<std::uint8_t>();
    v.water_depth.assign(v.height.size(), 0.0);  // dry unless a 'WAT1' chunk says otherwise
    v.lumped_area.assign(v.height.size(), 0.0);
    t.vertex_free_list = r.get_array<std::uint32_t>();
    t.slots = r.get_array<std::array<std::uint32_t, 3>>();
    t.slot_free_list = r.get_array<std::uint32_t>();
    t.constraint_capacity = r.get<std::uint32_t>();
    const auto count = r.get<std::uint64_t>();
    // Each constraint takes at least 20 bytes, which bounds a crafted count.
    if (count > r.remaining() / 20) r.fail("constraint count exceeds the file size");
    t.constraints.resize(count);
    for (ConstraintRecord& c : t.constraints) {
        c.id = r.get<std::uint32_t>();
        c.generation = r.get<Generation>();
        c.vertices = r.get_array<std::uint32_t>();
    }
    t.constraint_free_list = r.get_array<std::uint32_t>();
    return t;
}

/// About the bytes a session's payload takes (the terrain's arrays dominate), so that it is
/// written into one buffer; a little more or less only costs a reallocation.
std::size_t estimated_payload_bytes(const Session& session) {
    const TinSnapshot& t = session.terrain;
    const VertexArrays& v = t.vertices;
    std::size_t bytes = 4096 + session.metadata_json.size();
    bytes += v.size() * (sizeof(Vec2) + 3 * sizeof(double) + sizeof(std::uint16_t) + sizeof(float) +
                         sizeof(Vec2f) + sizeof(std::uint8_t));
    bytes += (t.vertex_free_list.size() + t.slot_free_list.size() + t.constraint_free_list.size()) *
             sizeof(std::uint32_t);
    bytes += t.slots.size() * sizeof(std::array<std::uint32_t, 3>);
    for (const ConstraintRecord& c : t.constraints)
        bytes += 32 + c.vertices.size() * sizeof(std::uint32_t);
    for (const auto& [id, body] : session.unknown_chunks)
        bytes += 12 + body.size();
    return bytes;
}

struct WaterChunk {
    std::uint32_t terrain_crc = 0;  ///< of the 'TIN1' body the depths were written with
    std::vector<double> depth;
};

/// Gives the terrain its water, or drops water written for another version of the terrain.
void attach_water(Session& session, std::uint32_t terrain_crc, WaterChunk water,
                  const ByteReader& r) {
    if (water.terrain_crc != terrain_crc) {
        session.stale_water_dropped = true;
        return;
    }
    VertexArrays& v = session.terrain.vertices;
    if (water.depth.size() != v.size()) {
        r.fail("the water chunk holds " + std::to_string(water.depth.size()) +
               " depths for a terrain of " + std::to_string(v.size()) + " vertex ids");
    }
    for (std::size_t i = 0; i < water.depth.size(); ++i) {
        if (!(water.depth[i] >= 0.0 && std::isfinite(water.depth[i]))) {
            r.fail("vertex " + std::to_string(i) + " has a negative or non-finite water depth");
        }
    }
    v.water_depth = std::move(water.depth);
}

}  // namespace

std::vector<std::uint8_t> encode_session(const Session& session) {
    // Header and chunks written into one buffer, the lengths and checksums filled in after
    // (a payload built apart and copied in cost two more copies of the whole file).
    ByteWriter file;
    file.reserve(kHeaderSize + estimated_payload_bytes(session));
    file.put_bytes(kMagic);
    file.put<std::uint32_t>(kSessionFormatVersion);
    file.put<std::uint32_t>(0);
    const std::size_t length_at = file.size();
    file.put<std::uint64_t>(0);  // payload length
    file.put<std::uint32_t>(0);  // payload CRC
    file.put<std::uint32_t>(0);  // header CRC
    const auto chunk = [&](std::uint32_t id, const auto& write_body) {
        file.put(id);
        const std::size_t size_at = file.size();
        file.put<std::uint64_t>(0);
        write_body();
        file.put_at<std::uint64_t>(size_at, file.size() - size_at - sizeof(std::uint64_t));
    };
    const std::size_t terrain_at = file.size() + sizeof(std::uint32_t) + sizeof(std::uint64_t);
    chunk(kTagTin, [&] { encode_terrain(file, session.terrain); });
    if (holds_water(session.terrain.vertices)) {
        const std::uint32_t terrain_crc =
            crc32_of(std::span(file.bytes()).subspan(terrain_at, file.size() - terrain_at));
        chunk(kTagWater, [&] {
            file.put<std::uint32_t>(terrain_crc);
            file.put_array<double>(session.terrain.vertices.water_depth);
        });
    }
    chunk(kTagGeneration, [&] { file.put<std::uint64_t>(session.next_generation); });
    chunk(kTagMeta, [&] {
        file.put_bytes(
            std::span(reinterpret_cast<const std::uint8_t*>(session.metadata_json.data()),
                      session.metadata_json.size()));
    });
    for (const auto& unknown : session.unknown_chunks)  // (clang 14 captures no bindings)
        chunk(unknown.first, [&] { file.put_bytes(unknown.second); });

    const std::span<const std::uint8_t> payload = std::span(file.bytes()).subspan(kHeaderSize);
    file.put_at<std::uint64_t>(length_at, payload.size());
    file.put_at<std::uint32_t>(length_at + 8, crc32_of(payload));
    file.put_at<std::uint32_t>(kHeaderChecked,
                               crc32_of(std::span(file.bytes()).first(kHeaderChecked)));
    return std::move(file.bytes());
}

Session decode_session(std::span<const std::uint8_t> bytes, const std::string& name) {
    ByteReader header(bytes, name);
    // A prefix of the magic (an empty file, a copy cut short) is a truncated session, which
    // is what the user needs to hear, not "not a session".
    if (bytes.size() < kMagic.size() &&
        (bytes.empty() || std::memcmp(bytes.data(), kMagic.data(), bytes.size()) == 0)) {
        header.fail("file is truncated: " + std::to_string(bytes.size()) +
                    " bytes, too few for a session's header" +
                    (bytes.empty() ? " (the file is empty)" : ""));
    }
    if (bytes.size() < kMagic.size() ||
        std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
        header.fail("not a sandtin session file (bad magic bytes)");
    }
    if (bytes.size() < kHeaderSize) header.fail("file is truncated: the header is incomplete");
    header.get_bytes(kMagic.size());
    const auto version = header.get<std::uint32_t>();
    std::uint32_t stored_header_crc = 0;
    std::memcpy(&stored_header_crc, bytes.data() + kHeaderChecked, 4);
    const bool header_intact = stored_header_crc == crc32_of(bytes.first(kHeaderChecked));
    if (version > kSessionFormatVersion) {
        // A newer format may lay its header out differently, so a checksum mismatch cannot
        // tell a damaged version field from a genuinely newer file: say both.
        header.fail("format version " + std::to_string(version) +
                    " is newer than this build supports (" + std::to_string(kSessionFormatVersion) +
                    "); update sandtin to open it" +
                    (header_intact ? "" : " (or the header is corrupted)"));
    }
    if (version < kOldestSessionFormatVersion) {
        header.fail("the header is corrupted (format version " + std::to_string(version) + ")");
    }
    header.get<std::uint32_t>();
    const auto length = header.get<std::uint64_t>();
    const auto crc = header.get<std::uint32_t>();
    header.get<std::uint32_t>();
    // Format 1 had no header checksum; from format 2 a damaged length or CRC field is caught
    // here rather than misreported as truncation.
    if (version >= 2 && !header_intact) {
        header.fail("header checksum mismatch: the file is corrupted");
    }
    if (length > header.remaining()) header.fail("file is truncated: payload is incomplete");
    if (length < header.remaining()) {
        // Named where they start, not where the header ends.
        header.get_bytes(length);
        header.fail("file has trailing bytes after the payload");
    }
    const auto payload = header.get_bytes(length);
    if (crc32_of(payload) != crc) header.fail("checksum mismatch: the file is corrupted");

    Session session;
    session.format_version = version;
    bool have_terrain = false;
    std::uint32_t terrain_crc = 0;
    std::optional<WaterChunk> water;
    ByteReader r(payload, name);
    while (!r.at_end()) {
        const auto id = r.get<std::uint32_t>();
        const auto size = r.get<std::uint64_t>();
        const auto body = r.get_bytes(size);
        ByteReader c(body, name);
        if (id == kTagTin) {
            session.terrain = decode_terrain(c);
            terrain_crc = crc32_of(body);
            have_terrain = true;
        } else if (id == kTagWater) {
            water = WaterChunk{c.get<std::uint32_t>(), c.get_array<double>()};
        } else if (id == kTagGeneration) {
            session.next_generation = c.get<std::uint64_t>();
        } else if (id == kTagMeta) {
            session.metadata_json.assign(body.begin(), body.end());
            continue;
        } else {
            session.unknown_chunks[id] = std::vector<std::uint8_t>(body.begin(), body.end());
            continue;
        }
        if (!c.at_end()) c.fail("chunk has unexpected trailing bytes");
    }
    if (!have_terrain) r.fail("file holds no terrain");
    if (water) attach_water(session, terrain_crc, std::move(*water), r);
    return session;
}

void save_session(const std::filesystem::path& path, const Session& session,
                  const WriteInterruption& interruption) {
    const std::vector<std::uint8_t> bytes = encode_session(session);
    write_file_atomically(path, bytes, interruption);
}

Session load_session(const std::filesystem::path& path) {
    const std::vector<std::uint8_t> bytes = read_file(path);
    return decode_session(bytes, path.string());
}

}  // namespace sandtin
