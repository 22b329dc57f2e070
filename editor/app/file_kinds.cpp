#include "file_kinds.hpp"

#include "util/lower_extension.hpp"

namespace sandtin::editor {

FileKind file_kind(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == kSceneExtension) return FileKind::Scene;
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
