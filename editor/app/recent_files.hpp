#pragma once
// The File panel's recent files: the last scenes and heightmaps opened, saved or imported,
// newest first, kept in the settings file (editor_settings.hpp).

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace sandtin::editor {

inline constexpr std::size_t kRecentFilesKept = 10;

/// `path` (made absolute, so the list means the same from any working directory) becomes the
/// newest entry; an older entry for the same path goes, and the oldest beyond
/// kRecentFilesKept fall off.
void note_recent_file(std::vector<std::string>& recent, const std::filesystem::path& path);

/// The list as a settings file may hold it after a hand edit, made one the panel can show:
/// no empty entries, no repeats (the first, newest, stays), at most kRecentFilesKept.
std::vector<std::string> tidy_recent_files(const std::vector<std::string>& recent);

}  // namespace sandtin::editor
