#include "folder_listing.hpp"

#include <algorithm>
#include <cctype>

namespace sandtin::editor {

namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

}  // namespace

FolderListing read_folder(const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    FolderListing listing;
    listing.folder = folder;
    std::error_code ec;
    if (!fs::exists(folder, ec)) {
        listing.error = folder.string() + " does not exist";
        return listing;
    }
    if (!fs::is_directory(folder, ec)) {
        listing.error = folder.string() + " is not a folder";
        return listing;
    }
    fs::directory_iterator it(folder, ec);
    for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
        std::error_code type_ec;
        // A link to a folder is a folder; a broken link, a file that cannot be opened.
        const bool is_folder = it->is_directory(type_ec);
        listing.entries.push_back({it->path().filename().string(), is_folder && !type_ec});
    }
    if (ec) {
        listing.error = "cannot read " + folder.string() + ": " + ec.message();
        listing.entries.clear();
        return listing;
    }
    std::sort(listing.entries.begin(), listing.entries.end(),
              [](const FolderEntry& a, const FolderEntry& b) {
                  if (a.folder != b.folder) return a.folder;
                  const std::string la = lower(a.name), lb = lower(b.name);
                  return la != lb ? la < lb : a.name < b.name;
              });
    return listing;
}

std::vector<FolderEntry> visible_entries(const std::vector<FolderEntry>& entries,
                                         const FileFilter& filter, std::string_view text,
                                         bool show_hidden) {
    const std::string wanted = lower(text);
    std::vector<FolderEntry> shown;
    for (const FolderEntry& e : entries) {
        if (!show_hidden && !e.name.empty() && e.name.front() == '.') continue;
        if (!e.folder && !filter.matches(e.name)) continue;
        if (!wanted.empty() && lower(e.name).find(wanted) == std::string::npos) continue;
        shown.push_back(e);
    }
    return shown;
}

}  // namespace sandtin::editor
