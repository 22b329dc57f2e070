#pragma once
// Deterministic replay of a recorded live session: the recorded edits, in order, through a
// fresh LiveEditor with the recorded tool and settings, starting from the recorded stamp
// generation. The same starting terrain gives the same terrain, bit for bit.

#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "haptics/haptic_recording.hpp"
#include "io/script.hpp"
#include "tin/tin.hpp"
#include "tools/sculpt_context.hpp"

namespace sandtin::haptics {

/// Replays into `tin`. Throws std::runtime_error when the terrain is not the one the session
/// started from (vertex count or volume differ from "start"), and JsonInputError for a bad
/// tool. `base_dir` resolves the tool's relative profile files. Returns a JSON report: edits,
/// stamps, volume change, ticks and the largest recorded force, and whether the result
/// matches the recording's "result".
nlohmann::json replay_recording(const HapticRecording& recording, Tin& tin, SculptContext& context,
                                const std::filesystem::path& base_dir);

/// A script equivalent to a recording, for `sandtin run`: the recording's terrain (if any)
/// and one custom operation, "haptic_replay", that calls replay_recording.
Script recording_script(std::string_view text, const std::string& name,
                        const std::filesystem::path& base_dir);

}  // namespace sandtin::haptics
