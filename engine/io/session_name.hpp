#pragma once
// Which names a session may be written under: never one that claims another format.

#include <filesystem>
#include <optional>
#include <string>

namespace sandtin {

/// Why `path` must not name a session file: it ends in the extension of a mesh, map,
/// heightmap or script (.obj .png .tif .json ...), so the session would be mistaken for that
/// format, and an export was probably meant. None when the name is fine. The message says
/// what to do ("...; name it .sandtin"); the caller adds what was being written and where
/// exports are made (`sandtin export`, the editor's Export button).
std::optional<std::string> session_name_problem(const std::filesystem::path& path);

}  // namespace sandtin
