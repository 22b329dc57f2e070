#pragma once
// The editor's own file browser, for a desktop without a dialog program (or when one is asked
// for: SANDTIN_FILE_DIALOG=imgui): what it shows and what a click, a double click or Enter
// does, without the UI. The panel that draws it with ImGui is panel_file_browser.cpp; this
// part is unit-tested (tests/editor/file_browser_test.cpp).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "file_dialog_request.hpp"
#include "folder_listing.hpp"

namespace sandtin::editor {

class FileBrowser {
  public:
    /// Shows `request`, in its folder.
    void open(FileDialogRequest request);
    void close();
    bool is_open() const { return open_; }
    const FileDialogRequest& request() const { return request_; }

    const std::filesystem::path& folder() const { return listing_.folder; }
    /// Why the folder cannot be listed, or "".
    const std::string& error() const { return listing_.error; }
    /// Why the last pick did not happen ("no file x.sandtin in /data"), or "".
    const std::string& message() const { return message_; }

    /// Goes to `folder` (a relative one from the current folder; "~" is the home folder). One
    /// that cannot be read
    /// becomes the browser's folder all the same, with its error shown and Up to leave it.
    void navigate(const std::filesystem::path& folder);
    void up();
    /// Reads the current folder again.
    void refresh() { navigate(folder()); }

    // What the artist sets in the dialog.
    std::size_t filter_index = 0;  ///< into request().filters
    std::string text;              ///< type to filter: a part of the names shown
    std::string name;              ///< the file name field
    bool show_hidden = false;      ///< names beginning with a dot

    const FileFilter& filter() const;
    /// The entries shown, folders first (folder_listing.hpp).
    std::vector<FolderEntry> visible() const;
    /// The name last clicked ("" for none): highlighted in the list.
    const std::string& selected() const { return selected_; }

    // What picks. Each returns the file picked (and closes the browser), or nothing: a folder
    // was entered, a message says why not, or the overwrite question waits.
    /// A click: the entry is selected, and a file's name goes to the name field.
    void select(const FolderEntry& entry);
    /// A double click: a folder is entered, a file picked.
    std::optional<std::filesystem::path> activate(const FolderEntry& entry);
    /// Enter in the type-to-filter box: the one file shown is picked (or the one named exactly
    /// as typed); with no file shown, the one folder shown is entered.
    std::optional<std::filesystem::path> accept_filter();
    /// The pick button, or Enter in the name field: the name field's file (a relative name is
    /// in the current folder; a folder named is entered). When saving, a name without an
    /// extension gets the request's first one, and an existing file is replaced only after
    /// the overwrite question (when the request asks it).
    std::optional<std::filesystem::path> accept();
    /// A file that exists, waiting for the overwrite answer.
    const std::optional<std::filesystem::path>& replacing() const { return replacing_; }
    std::optional<std::filesystem::path> answer_overwrite(bool replace);

  private:
    std::optional<std::filesystem::path> pick(const std::filesystem::path& path);

    bool open_ = false;
    FileDialogRequest request_;
    FolderListing listing_;
    std::string selected_;
    std::string message_;
    std::optional<std::filesystem::path> replacing_;
};

}  // namespace sandtin::editor
