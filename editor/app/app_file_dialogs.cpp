// Open..., Save As..., Import... and Export...: which dialog shows (the desktop's program or
// the editor's own browser), where it starts, and what becomes of the file picked in it. The
// dialogs themselves are native_file_dialog.cpp and file_browser.cpp.

#include "app.hpp"

#include <cstdlib>

namespace sandtin::editor {

namespace fs = std::filesystem;

namespace {

const char* env_or(const char* name, const char* fallback) {
    const char* v = std::getenv(name);
    return v != nullptr ? v : fallback;
}

}  // namespace

std::optional<DialogProgram> App::native_dialog_program() {
    std::string mode = settings_.file_dialog;
    if (const char* env = std::getenv("SANDTIN_FILE_DIALOG"); env != nullptr && *env != '\0') {
        mode = env;
        if (mode != "auto" && mode != "native" && mode != "imgui") {
            report("SANDTIN_FILE_DIALOG=" + mode + " is not auto, native or imgui: auto is used");
            mode = "auto";
        }
    }
    if (mode == "imgui" || (mode == "auto" && options_.scripted())) return std::nullopt;
    std::optional<DialogProgram> program =
        find_dialog_program(env_or("PATH", ""), env_or("XDG_CURRENT_DESKTOP", ""));
    if (!program && mode == "native")
        report("no zenity or kdialog on PATH: the editor's own file browser is used");
    return program;
}

fs::path App::dialog_start_folder(FileDialogKind kind) const {
    std::error_code ec;
    if (!settings_.last_folder.empty() && fs::is_directory(settings_.last_folder, ec))
        return settings_.last_folder;
    const char* field = kind == FileDialogKind::Import   ? import_buf_
                        : kind == FileDialogKind::Export ? export_buf_
                                                         : path_buf_;
    const fs::path folder = fs::absolute(fs::path(field), ec).parent_path();
    if (!ec && fs::is_directory(folder, ec)) return folder;
    return fs::current_path(ec);
}

void App::show_file_dialog(FileDialogKind kind) {
    if (file_dialog_open()) {
        report("a file dialog is open already: answer it first");
        return;
    }
    // Save As and Export propose the name in their field.
    const std::string name =
        fs::path(kind == FileDialogKind::Export ? export_buf_ : path_buf_).filename().string();
    const FileDialogRequest request = file_dialog_request(kind, dialog_start_folder(kind), name);
    if (const std::optional<DialogProgram> program = native_dialog_program()) {
        if (!native_dialog_) {
            // Called on the dialog's thread: GLFW allows posting an empty event from any thread,
            // and it wakes a loop blocked waiting for input to draw the frame that takes the
            // answer.
            native_dialog_ = std::make_unique<NativeFileDialog>([] { glfwPostEmptyEvent(); });
        }
        native_request_ = request;
        native_dialog_->start(*program, request);
        return;
    }
    browser_.open(request);
    redraw_frames_ = std::max(redraw_frames_, 2);
}

void App::take_native_dialog_result() {
    if (!native_dialog_) return;
    const std::optional<NativeDialogResult> r = native_dialog_->take_result();
    if (!r) return;
    redraw_frames_ = std::max(redraw_frames_, 2);
    switch (r->outcome) {
        case NativeDialogResult::Outcome::Chosen:
            apply_picked_file(native_request_.kind, r->path);
            break;
        case NativeDialogResult::Outcome::Cancelled:
            break;
        case NativeDialogResult::Outcome::Failed:
            report("the file dialog failed (" + r->error + "): the editor's own browser instead");
            browser_.open(native_request_);
            break;
    }
}

void App::apply_picked_file(FileDialogKind kind, const fs::path& path) {
    settings_.last_folder = path.parent_path().string();
    guarded("file dialog", [&] {
        switch (kind) {
            case FileDialogKind::Open:
                // The Scene field takes the path when the scene opens (open_reporting): until
                // then it is where Save writes the untitled scene the prompt may ask about.
                replace_document("Open", [this, path] { open_reporting(path); });
                break;
            case FileDialogKind::SaveAs:
                set_scene_field(path.string());
                request_save(path);
                break;
            case FileDialogKind::Import:
                set_import_field(path.string());
                replace_document("Import", [this, path] { import_document(path); });
                break;
            case FileDialogKind::Export:
                set_export_field(path.string());
                export_reporting(path);
                break;
        }
    });
}

}  // namespace sandtin::editor
