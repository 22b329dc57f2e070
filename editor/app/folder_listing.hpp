#pragma once
// A folder's contents as the editor's file browser lists them (file_browser.hpp): read once
// (read_folder), then shown through the browser's filters (visible_entries) as the artist types,
// without reading the folder again. No UI here: tests/editor/file_browser_test.cpp checks it on
// temporary folders.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "file_dialog_request.hpp"

namespace sandtin::editor {

struct FolderEntry {
    std::string name;
    bool folder = false;  ///< a folder, or a link to one
    friend bool operator==(const FolderEntry&, const FolderEntry&) = default;
};

struct FolderListing {
    std::filesystem::path folder;
    /// Folders first, then files, each by name, case aside.
    std::vector<FolderEntry> entries;
    /// Why the folder could not be read ("" when it was): it does not exist, is a file, or may
    /// not be listed. The entries are then empty.
    std::string error;
};

/// Lists `folder` (never throws: a folder that cannot be read gives `error`).
FolderListing read_folder(const std::filesystem::path& folder);

/// The entries shown: folders always (the way to the files), files that pass `filter`; each
/// only when its name holds `text` (case aside); names beginning with a dot only when
/// `show_hidden`. In `entries`' order.
std::vector<FolderEntry> visible_entries(const std::vector<FolderEntry>& entries,
                                         const FileFilter& filter, std::string_view text,
                                         bool show_hidden);

}  // namespace sandtin::editor
