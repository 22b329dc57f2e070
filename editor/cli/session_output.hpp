#pragma once
// The -o of the commands that write a session (new, import, run, haptics serve).

#include <filesystem>

namespace sandtin::cli {

/// Throws UsageError when `path` is not writable now (check_writable) or ends in the extension
/// of a mesh, map or heightmap (.obj .png .tif ...): a session written there would be
/// mistaken for that format, and `sandtin export` was probably meant.
void check_session_output(const std::filesystem::path& path);

}  // namespace sandtin::cli
