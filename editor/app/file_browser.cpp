#include "file_browser.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace sandtin::editor {

namespace fs = std::filesystem;

void FileBrowser::open(FileDialogRequest request) {
    request_ = std::move(request);
    open_ = true;
    filter_index = 0;
    name = request_.name;
    show_hidden = false;
    message_.clear();
    replacing_.reset();
    std::error_code ec;  // a working folder that is gone: "" (the error shows in the browser)
    navigate(request_.folder.empty() ? fs::current_path(ec) : request_.folder);
}

void FileBrowser::close() {
    open_ = false;
    replacing_.reset();
}

void FileBrowser::navigate(const fs::path& folder) {
    fs::path target = folder;
    // "~" and "~/maps" are in the home folder, as in a shell.
    const std::string typed = folder.string();
    const char* home = std::getenv("HOME");
    if (home != nullptr && *home != '\0' && (typed == "~" || typed.rfind("~/", 0) == 0))
        target = fs::path(home) / typed.substr(typed.size() > 1 ? 2 : 1);
    if (target.is_relative()) target = listing_.folder / target;
    std::error_code ec;
    if (target.is_relative()) target = fs::absolute(target, ec);
    target = target.lexically_normal();
    // "/data/" and "/data" are one folder: shown, and remembered, without the separator.
    if (target.has_relative_path() && !target.has_filename()) target = target.parent_path();
    listing_ = read_folder(target);
    text.clear();
    selected_.clear();
    message_.clear();
}

void FileBrowser::up() {
    const fs::path parent = folder().parent_path();
    if (!parent.empty() && parent != folder()) navigate(parent);
}

const FileFilter& FileBrowser::filter() const {
    static const FileFilter kAll{"All files", {}};
    return filter_index < request_.filters.size() ? request_.filters[filter_index] : kAll;
}

std::vector<FolderEntry> FileBrowser::visible() const {
    return visible_entries(listing_.entries, filter(), text, show_hidden);
}

void FileBrowser::select(const FolderEntry& entry) {
    selected_ = entry.name;
    message_.clear();
    if (!entry.folder) name = entry.name;
}

std::optional<fs::path> FileBrowser::activate(const FolderEntry& entry) {
    if (entry.folder) {
        navigate(folder() / entry.name);
        return std::nullopt;
    }
    name = entry.name;
    return accept();
}

std::optional<fs::path> FileBrowser::accept_filter() {
    const std::vector<FolderEntry> shown = visible();
    std::vector<FolderEntry> files;
    std::copy_if(shown.begin(), shown.end(), std::back_inserter(files),
                 [](const FolderEntry& e) { return !e.folder; });
    for (const FolderEntry& f : files) {
        if (f.name == text) return activate(f);
    }
    if (files.size() == 1) return activate(files.front());
    if (files.empty() && shown.size() == 1) return activate(shown.front());
    message_ = files.empty() ? "nothing here matches '" + text + "'"
                             : std::to_string(files.size()) + " files match: click one";
    return std::nullopt;
}

std::optional<fs::path> FileBrowser::accept() {
    message_.clear();
    const std::size_t first = name.find_first_not_of(" \t");
    const std::size_t last = name.find_last_not_of(" \t");
    if (first == std::string::npos) {
        message_ = request_.saving ? "type a file name" : "choose a file";
        return std::nullopt;
    }
    fs::path p = name.substr(first, last - first + 1);
    p = (p.is_relative() ? folder() / p : p).lexically_normal();
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
        navigate(p);
        name.clear();
        return std::nullopt;
    }
    if (!request_.saving) {
        if (!fs::is_regular_file(p, ec)) {
            message_ = "no file " + p.filename().string() + " in " + p.parent_path().string();
            return std::nullopt;
        }
        return pick(p);
    }
    if (p.extension().empty() && !request_.filters.empty() &&
        !request_.filters.front().extensions.empty())
        p += request_.filters.front().extensions.front();
    if (!fs::is_directory(p.parent_path(), ec)) {
        message_ = "there is no folder " + p.parent_path().string();
        return std::nullopt;
    }
    if (fs::is_directory(p, ec)) {
        navigate(p);
        name.clear();
        return std::nullopt;
    }
    if (request_.confirm_overwrite && fs::exists(p, ec)) {
        replacing_ = p;
        return std::nullopt;
    }
    return pick(p);
}

std::optional<fs::path> FileBrowser::answer_overwrite(bool replace) {
    if (!replacing_) return std::nullopt;
    const fs::path p = *replacing_;
    replacing_.reset();
    if (!replace) {
        message_ = "not replaced: type another name";
        return std::nullopt;
    }
    return pick(p);
}

std::optional<fs::path> FileBrowser::pick(const fs::path& path) {
    close();
    return path;
}

}  // namespace sandtin::editor
