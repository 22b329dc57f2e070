#pragma once
// How old an autosave is, in words, for the recovery prompt: the artist decides whether to
// recover by whether it is the work of a few minutes ago or of last week.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

namespace sandtin::editor {

/// "autosave from 3 minutes ago, 14:02" (local time; the date too when it is not today's):
/// an autosave written at `written`, read at `now`. A time ahead of `now` (a clock set back)
/// gets no age, only its time.
std::string autosave_age_text(std::chrono::system_clock::time_point written,
                              std::chrono::system_clock::time_point now);

/// When the autosave of the scene at `scene` was last written, or nullopt when there is none
/// or its time cannot be read.
std::optional<std::chrono::system_clock::time_point> autosave_written_at(
    const std::filesystem::path& scene);

}  // namespace sandtin::editor
