#include "file_dialog_request.hpp"

#include "file_kinds.hpp"
#include "util/lower_extension.hpp"

namespace sandtin::editor {

namespace {

template <std::size_t N>
FileFilter filter_of(const std::string& what, const char* const (&extensions)[N]) {
    FileFilter f;
    f.label = what + " (";
    for (const char* e : extensions) {
        f.label += (f.extensions.empty() ? "" : " ") + std::string(e);
        f.extensions.emplace_back(e);
    }
    f.label += ")";
    return f;
}

}  // namespace

bool FileFilter::matches(const std::filesystem::path& path) const {
    if (extensions.empty()) return true;
    const std::string ext = lower_extension(path);
    for (const std::string& e : extensions) {
        if (ext == e) return true;
    }
    return false;
}

FileDialogRequest file_dialog_request(FileDialogKind kind, const std::filesystem::path& folder,
                                      const std::string& name) {
    static constexpr const char* kScene[] = {kSceneExtension};
    FileDialogRequest r;
    r.kind = kind;
    r.folder = folder;
    switch (kind) {
        case FileDialogKind::Open:
            r.title = "Open a scene";
            r.action = "Open";
            r.filters.push_back(filter_of("Scenes", kScene));
            break;
        case FileDialogKind::SaveAs:
            r.title = "Save the scene as";
            r.action = "Save";
            r.saving = true;
            r.filters.push_back(filter_of("Scenes", kScene));
            break;
        case FileDialogKind::Import:
            r.title = "Import a heightmap";
            r.action = "Import";
            r.filters.push_back(filter_of("Heightmaps", kHeightmapExtensions));
            break;
        case FileDialogKind::Export:
            r.title = "Export the terrain";
            r.action = "Export";
            r.saving = true;
            r.confirm_overwrite = true;
            r.filters.push_back(filter_of("Meshes and height maps", kExportExtensions));
            break;
    }
    if (r.saving) r.name = name;
    r.filters.push_back({"All files", {}});
    return r;
}

const char* to_string(FileDialogKind kind) {
    switch (kind) {
        case FileDialogKind::Open:
            return "open";
        case FileDialogKind::SaveAs:
            return "save_as";
        case FileDialogKind::Import:
            return "import";
        case FileDialogKind::Export:
            return "export";
    }
    return "?";
}

std::optional<FileDialogKind> file_dialog_kind_named(std::string_view name) {
    for (FileDialogKind k : {FileDialogKind::Open, FileDialogKind::SaveAs, FileDialogKind::Import,
                             FileDialogKind::Export}) {
        if (name == to_string(k)) return k;
    }
    return std::nullopt;
}

}  // namespace sandtin::editor
