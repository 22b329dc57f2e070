#pragma once
// The shell command that opens a scene in the editor, for commands that tell the user how to
// look at what they wrote (`sandtin demo`).

#include <filesystem>
#include <string>

namespace sandtin::cli {

/// "build/editor/app/sandtin-editor scene.sandtin": the editor built beside this sandtin binary
/// (editor/app/sandtin-editor next to editor/cli/sandtin in the build tree) when it exists,
/// otherwise `sandtin-editor` as found on PATH. Paths under the current directory are given
/// relative to it, others absolute; words the shell would split or expand are quoted.
std::string editor_command(const std::filesystem::path& scene);

/// `path` relative to the current directory when it lies under it, else absolute.
std::filesystem::path path_for_display(const std::filesystem::path& path);

/// `word` as one shell word: as it is when it holds only safe characters, else single-quoted.
std::string shell_quote(const std::string& word);

}  // namespace sandtin::cli
