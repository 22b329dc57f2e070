#pragma once
// What a file dialog is asked for, whichever shows it (the desktop's dialog program,
// native_file_dialog.hpp, or the editor's own browser, file_browser.hpp): Open a scene, Save
// it As, Import a heightmap or Export the terrain, with the extensions each takes
// (file_kinds.hpp), where it starts and the name it proposes.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sandtin::editor {

enum class FileDialogKind { Open, SaveAs, Import, Export };

/// A choice of the dialog's filter: files with one of `extensions` (lower case, with the dot;
/// compared case aside), or every file when it has none.
struct FileFilter {
    std::string label;  ///< "Scenes (.sandtin)"
    std::vector<std::string> extensions;

    /// Whether a file named `path` passes (folders are never filtered).
    bool matches(const std::filesystem::path& path) const;
    friend bool operator==(const FileFilter&, const FileFilter&) = default;
};

struct FileDialogRequest {
    FileDialogKind kind = FileDialogKind::Open;
    std::string title;   ///< "Open a scene"
    std::string action;  ///< the button that picks: "Open", "Save", "Import", "Export"
    /// A name may be typed, and the file need not exist yet (Save As, Export).
    bool saving = false;
    /// The dialog itself asks before an existing file is picked (Export). Save As does not:
    /// the editor's own prompt asks then, and knows about the autosave a file may have.
    bool confirm_overwrite = false;
    std::filesystem::path folder;  ///< where the dialog starts
    std::string name;              ///< the file name proposed when saving
    /// The first is chosen at first; the last is "All files".
    std::vector<FileFilter> filters;
};

/// The request for `kind`, starting in `folder`, proposing `name` when saving.
FileDialogRequest file_dialog_request(FileDialogKind kind, const std::filesystem::path& folder,
                                      const std::string& name = {});

/// "open", "save_as", "import", "export": as a script names them.
const char* to_string(FileDialogKind kind);
std::optional<FileDialogKind> file_dialog_kind_named(std::string_view name);

}  // namespace sandtin::editor
