#include "file_kinds.hpp"

#include <algorithm>
#include <cctype>

namespace sandtin::editor {

FileKind file_kind(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".sandtin") return FileKind::Scene;
    for (const char* e : kHeightmapExtensions) {
        if (ext == e) return FileKind::Heightmap;
    }
    return FileKind::Other;
}

std::string accepted_files_text() {
    std::string text = "a scene (.sandtin) or a heightmap (";
    for (const char* e : kHeightmapExtensions)
        text += std::string(text.back() == '(' ? "" : " ") + e;
    return text + ")";
}

}  // namespace sandtin::editor
