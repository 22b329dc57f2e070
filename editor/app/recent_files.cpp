#include "recent_files.hpp"

#include <algorithm>

namespace sandtin::editor {

void note_recent_file(std::vector<std::string>& recent, const std::filesystem::path& path) {
    std::error_code ec;
    std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    if (ec) absolute = path;
    const std::string entry = absolute.lexically_normal().string();
    std::erase(recent, entry);
    recent.insert(recent.begin(), entry);
    if (recent.size() > kRecentFilesKept) recent.resize(kRecentFilesKept);
}

std::vector<std::string> tidy_recent_files(const std::vector<std::string>& recent) {
    std::vector<std::string> tidy;
    for (const std::string& entry : recent) {
        if (entry.empty() || std::find(tidy.begin(), tidy.end(), entry) != tidy.end()) continue;
        tidy.push_back(entry);
        if (tidy.size() == kRecentFilesKept) break;
    }
    return tidy;
}

}  // namespace sandtin::editor
