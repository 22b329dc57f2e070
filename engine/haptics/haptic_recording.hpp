#pragma once
// Recorded live-editing sessions: what the device did at every loop tick (pose, buttons, the
// force rendered), the device states the simulation consumed (the edits), and everything
// needed to replay those edits into the same terrain: the tool, the editing settings, the
// starting terrain and stamp generation. `sandtin run recording.json` replays one.
//
// JSON (".haptic.json"):
//   { "format": "sandtin-haptic-recording", "version": 1,
//     "rate_hz": 1000,
//     "tool": { ...a tool object, as in scripts... },
//     "edit": { "spacing": 0.005, "erode_iterations": 0, "button_mask": 1,
//               "relocation_radius": 0, "damping": 0.5, "rest_tolerance": 0.0001 },
//     "terrain": { "size": [1, 1], "points": 0, "seed": 1, "height": 0.05 },   (optional;
//                 without it the terrain comes from `sandtin run -i`)
//     "start": { "next_generation": 1, "vertices": 4, "volume": 0.05 },
//     "ticks": [[x, y, z, buttons, fx, fy, fz], ...],     one per loop tick (m, N)
//     "edits": [[tick, x, y, z, buttons], ...],           in the order the simulation used them
//     "result": { "vertices": 1234, "volume": 0.0493 } }   (optional) the live terrain after
//                                                           the last edit
// Numbers are written with round-trip precision, so a replay sees bit-identical inputs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "haptics/live_editor.hpp"
#include "io/script.hpp"

namespace sandtin::haptics {

inline constexpr std::string_view kRecordingFormat = "sandtin-haptic-recording";
inline constexpr int kRecordingVersion = 1;

struct RecordedTick {
    Vec3 position;  ///< m
    std::uint32_t buttons = 0;
    Vec3 force;  ///< N
    friend bool operator==(const RecordedTick&, const RecordedTick&) = default;
};

struct TerrainSummary {
    std::size_t vertices = 0;
    double volume = 0.0;  ///< m³ above z = 0
    friend bool operator==(const TerrainSummary&, const TerrainSummary&) = default;
};
TerrainSummary summarise(const Tin& tin);

struct HapticRecording {
    double rate_hz = 1000.0;
    nlohmann::json tool = nlohmann::json::object();
    LiveEditSettings edit;
    std::optional<ScriptTerrain> terrain;
    Generation next_generation = 1;
    std::optional<TerrainSummary> start;
    std::vector<RecordedTick> ticks;
    std::vector<EditInput> edits;
    std::optional<TerrainSummary> result;
};

nlohmann::json recording_to_json(const HapticRecording& recording);
/// Throws JsonInputError naming `name` and the field.
HapticRecording recording_from_json(const nlohmann::json& j, const std::string& name);

std::string format_recording(const HapticRecording& recording);
HapticRecording parse_recording(std::string_view text, const std::string& name);
/// True when `text` is a JSON object whose "format" is sandtin-haptic-recording.
bool is_haptic_recording(std::string_view text);

void save_recording(const std::filesystem::path& path, const HapticRecording& recording);
HapticRecording load_recording(const std::filesystem::path& path);

/// The terrain a recording's "terrain" object describes (same construction as scripts').
Tin make_recording_terrain(const ScriptTerrain& terrain, TinOptions options = {});

}  // namespace sandtin::haptics
