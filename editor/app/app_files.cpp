// Files handed to the editor without a field to type them into: dropped on the window, or
// picked from the File panel's recent list. Both go the way the Open and Import buttons go,
// so the unsaved-edits prompt guards them as it guards the buttons.

#include "app.hpp"

namespace sandtin::editor {

void App::open_or_import(const std::filesystem::path& path, FileKind kind) {
    switch (kind) {
        case FileKind::Scene:
            replace_document("Open", [this, path] { open_reporting(path); });
            break;
        case FileKind::Heightmap:
            replace_document("Import", [this, path] { import_document(path); });
            break;
        case FileKind::Other:
            report("cannot open " + path.string() + ": the editor takes " + accepted_files_text());
            break;
    }
}

void App::drop_files(const std::vector<std::string>& paths) {
    if (paths.empty()) return;
    const std::filesystem::path first = paths.front();
    // A prompt waiting for its answer is about the scene open now: a drop must not replace
    // that scene under it (as shortcuts do not, App::key).
    if (prompt_open()) {
        report("answer the open prompt first: " + first.string() + " was not opened");
        return;
    }
    if (refuse_while_busy("opening the dropped " + first.string())) return;
    // One scene is open at a time: the first file counts, and the status line says what was
    // left (open_or_import's own message follows it in the session's messages).
    if (paths.size() > 1)
        report(std::to_string(paths.size() - 1) + " more dropped file(s) ignored: one at a time");
    open_or_import(first, file_kind(first));
}

}  // namespace sandtin::editor
