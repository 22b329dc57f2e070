#pragma once
// Native session files (.sandtin): the terrain and the editing state around it.
//
// Layout (little-endian):
//   header:  magic "SANDTIN\x1a", u32 format version, u32 reserved (0),
//            u64 payload length, u32 CRC-32 of the payload, u32 CRC-32 of the header's first
//            28 bytes (format 2; 0 in format 1, which had no header checksum)
//   payload: chunks of {u32 tag, u64 length, bytes}. Readers skip unknown tags and keep
//            them, so a newer minor addition survives a round trip through an older build.
//   chunks:  'TIN1' the TinSnapshot, 'GEN1' the next generation, 'META' a JSON object of
//            session metadata, and 'WAT1' (only when some vertex holds water) the water:
//            u32 CRC-32 of the 'TIN1' body it belongs to, then the vertex arrays' water depths
//            (an array of f64, metres). A build that does not know 'WAT1' keeps it verbatim but
//            may rewrite the terrain: the CRC then no longer matches, and the water, which no
//            longer fits that terrain, is dropped on load (Session::stale_water_dropped).
// Files are written atomically (util/atomic_file.hpp). Format 1 files still load; every
// file is written as the current format.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tin/tin_snapshot.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {

inline constexpr std::uint32_t kSessionFormatVersion = 2;
inline constexpr std::uint32_t kOldestSessionFormatVersion = 1;

struct Session {
    TinSnapshot terrain;
    Generation next_generation = 1;    ///< generation the next tool stamp will use
    std::string metadata_json = "{}";  ///< free-form JSON object (scene name, tool settings, ...)
    std::map<std::uint32_t, std::vector<std::uint8_t>> unknown_chunks;  ///< kept verbatim
    /// The format the file was read from (decode only; encoding always writes the current
    /// one), so the editor can say a save will upgrade an older file.
    std::uint32_t format_version = kSessionFormatVersion;
    /// Decode only: the file held water for a terrain that a build without water support
    /// rewrote since, and the water was dropped (the terrain loaded dry).
    bool stale_water_dropped = false;
};

/// A session made when it is needed, on the thread that needs it (SessionKeeper::hand_out,
/// AutosaveWriter::submit). Called at most once.
using SessionSource = std::function<Session()>;

std::vector<std::uint8_t> encode_session(const Session& session);
/// Throws std::runtime_error with a message naming the problem (not a session, corrupted
/// header or payload, truncated, from a newer version, or structurally invalid terrain).
Session decode_session(std::span<const std::uint8_t> bytes, const std::string& name = "session");

void save_session(const std::filesystem::path& path, const Session& session,
                  const WriteInterruption& interruption = {});
Session load_session(const std::filesystem::path& path);

}  // namespace sandtin
