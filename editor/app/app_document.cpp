// The document commands as the app gives them: the prompts that guard them (unsaved edits, a
// file to replace, an autosave to recover), the one path by which a document replaces
// another, and what the status line says. The operations themselves are Document's.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "recent_files.hpp"
#include "terrain_scale.hpp"

namespace sandtin::editor {

namespace {

/// Whether `a` and `b` name the same file (either may not exist yet).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec;
    return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

}  // namespace

// ---- Replacing the document ---------------------------------------------------------------

void App::install_document(Document next, const std::string& message) {
    install(std::move(next), std::nullopt, message);
}

void App::install_document(PreparedDocument next, const std::string& message) {
    install(std::move(next.document), std::move(next.view), message);
}

void App::install(Document next, std::optional<PreparedView> prepared, const std::string& message) {
    const auto started = Clock::now();
    // What the old document had under way ends with it (its open level included).
    if (doc_.has_terrain()) sculpting_.close_level(doc_);
    sculpting_.reset();
    // Nothing a submitted frame or solver step may still read is destroyed before the GPU is
    // done with it; then the old document goes (its GPU solver with it), and everything built
    // for its terrain is built again for the new one before anything draws.
    window_->wait_idle();
    release_terrain();
    doc_ = std::move(next);
    cursor_.reset();
    erosion_active_ = 0;
    const std::string scaled = fit_settings_to_document();
    // The material the Paint brush and the pour use must be in this document's table.
    settings_.material =
        std::clamp(settings_.material, 0, static_cast<int>(doc_.materials().size()) - 1);
    if (prepared)
        view_->rebuild(doc_, std::move(*prepared));
    else
        view_->rebuild(doc_);
    attach_solver(false);
    // An opened scene was never relaxed by this solver (it may have been saved mid-slide, or
    // imported steeper than repose): all of it is a candidate, as after a switch of solver.
    // What is at rest leaves the active set after a few quiet iterations.
    doc_.solver().activate_all();
    sculpting_.kick();
    frame_terrain();
    if (install_ms_.size() < 100) install_ms_.push_back(elapsed_ms(started));
    std::string text = message;
    if (!scaled.empty()) text += text.empty() ? scaled : "; " + scaled;
    if (doc_.erosion_held() && settings_.erosion_running)
        text += std::string(text.empty() ? "" : "; ") + "erosion waits for Run";
    if (!text.empty()) report(text);
}

void App::new_document() {
    if (refuse_while_busy("new sandbox")) return;
    // Built on a worker with its view prepared, as an opened scene is: on the UI thread the
    // sandbox's 40 800 vertices took 156-233 ms of one frame to install, besides their build.
    start_document_job(
        "new", "New sandbox",
        [](const ProgressCallback& progress) {
            if (progress) progress({0.0, "building the sandbox"});
            return Document::sandbox();
        },
        [this](PreparedDocument next) {
            hand_unsaved_edits_to_autosave();
            install_document(std::move(next), "new sandbox");
        });
}

void App::answer_recovery(bool recover) {
    if (!recovery_for_) throw std::runtime_error("there is no autosave to recover or discard");
    const std::filesystem::path scene = *recovery_for_;
    recovery_for_.reset();
    autosave_writer_.cancel();  // nothing may rewrite the autosave being recovered or discarded
    if (recover) {
        // Read on a worker, as Open does. The autosave was checked when the scene opened, but it
        // can still fail now (its terrain may not rebuild): the scene stays as it is, and the
        // status line says why.
        recover_document(scene);
        return;
    }
    try {
        discard_autosave(scene);
        report("discarded the autosave of " + scene.string());
    } catch (const std::exception& e) {
        report(std::string("cannot discard the autosave: ") + e.what());
    }
}

void App::replace_document(const std::string& what, std::function<void()> action) {
    if (refuse_while_busy(what)) return;
    sculpting_.close_level(doc_);
    if (doc_.dirty() && doc_.untitled()) {
        pending_replacement_ = std::move(action);
        pending_replacement_label_ = what;
        return;
    }
    action();
}

void App::answer_discard(DiscardChoice choice) {
    if (!pending_replacement_) throw std::runtime_error("no unsaved edits wait to be discarded");
    std::function<void()> action = std::move(pending_replacement_);
    pending_replacement_ = nullptr;
    switch (choice) {
        case DiscardChoice::Save:
            // A failed (or cancelled) save keeps the scene, and the status line says why.
            request_save(save_path(), std::move(action));
            break;
        case DiscardChoice::Discard:
            action();
            break;
        case DiscardChoice::Cancel:
            report("kept the unsaved scene: save it with Save or Save As");
            break;
    }
}

bool App::close_confirmed() {
    GLFWwindow* w = window_->glfw();
    if (!glfwWindowShouldClose(w)) return false;
    if (quit_confirmed_ || !doc_.dirty() || !doc_.untitled()) return true;
    // Closing would drop an untitled scene's edits: stay open and ask (discard_prompt).
    glfwSetWindowShouldClose(w, GLFW_FALSE);
    replace_document("Quit", [this, w] {
        quit_confirmed_ = true;
        glfwSetWindowShouldClose(w, GLFW_TRUE);
    });
    redraw_frames_ = 3;
    return false;
}

// ---- Saving and exporting -----------------------------------------------------------------

void App::save_now(const std::filesystem::path& p) {
    sculpting_.close_level(doc_);
    // An autosave still being written would otherwise land after the save retired it.
    autosave_writer_.cancel();
    doc_.save(p);
    set_scene_field(p.string());
    note_recent_file(settings_.recent_files, p);
    report("saved " + p.string());
}

void App::request_save(const std::filesystem::path& p, std::function<void()> then) {
    if (refuse_while_busy("save")) return;
    sculpting_.close_level(doc_);
    std::error_code ec;
    const bool own_file = !doc_.untitled() && same_file(p, doc_.path());
    // Another scene's file, or the autosave that keeps another scene's unsaved edits, is
    // replaced only when the artist says so.
    if (!own_file && (std::filesystem::exists(p, ec) || find_autosave(p))) {
        pending_overwrite_ = PendingOverwrite{p, std::move(then)};
        return;
    }
    save(p, std::move(then));
}

void App::keep_unsaved_edits() {
    hand_unsaved_edits_to_autosave();
    autosave_writer_.flush();
    if (const std::optional<std::string> error = autosave_writer_.take_error())
        report("autosave failed: " + *error);
}

void App::hand_unsaved_edits_to_autosave() {
    if (autosaves() && doc_.keep_in_autosave(autosave_writer_))
        report("unsaved edits of " + doc_.path().string() + " kept in its autosave");
}

void App::autosave_if_due() {
    const auto now = Clock::now();
    if (const std::optional<AutosaveWriter::Failure> failure = autosave_writer_.take_failure()) {
        if (doc_.path() == failure->scene) {
            report("autosave failed, will retry: " + failure->message);
            doc_.mark_edited(now);  // due again one interval from now
        } else {
            // A scene the editor has left (its edits were handed over as it was replaced).
            report("autosave failed: " + failure->message);
        }
    }
    if (autosaves()) doc_.autosave_if_due(autosave_writer_, now);
}

// ---- Undo and material edits --------------------------------------------------------------

void App::undo() {
    sculpting_.close_level(doc_);
    UndoOutcome u = doc_.undo();
    // A stroke's level holds its settling, so what it restores was at rest and the erosion
    // runs on. A level of erosion alone (Run on a scene steeper than repose, a material made
    // steeper) restores sand that is not at rest: running on, the physics would slide it
    // straight back and undo the undo, so the erosion pauses there, and says so.
    if (u.restored_erosion && erosion_runs()) {
        settings_.erosion_running = false;
        u.message += "; erosion paused (Run slides it again)";
    }
    report(u.message);
    sculpting_.kick();
}

void App::redo() {
    sculpting_.close_level(doc_);
    report(doc_.redo().message);
    sculpting_.kick();
}

void App::edit_material(int index, const Material& m) {
    sculpting_.close_level(doc_);
    doc_.edit_material(index, m);
    sculpting_.kick();
}

// ---- What follows the document's terrain ---------------------------------------------------

void App::frame_terrain() {
    const Rect d = doc_.tin().domain();
    const VertexArrays& va = doc_.tin().vertices();
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        lo = std::min(lo, va.height[i]);
        hi = std::max(hi, va.height[i]);
    }
    int w = 0, h = 0;
    window_->window_size(w, h);
    // The whole terrain where the panel does not cover it; in a window too narrow for that,
    // the whole terrain in the whole view.
    camera_.frame_in({-0.5 * d.width(), -0.5 * d.height(), lo},
                     {0.5 * d.width(), 0.5 * d.height(), hi}, w, h, free_viewport(w, h));
}

std::string App::fit_settings_to_document() {
    const double size = terrain_size(doc_.tin().domain());
    const double k = fit_settings_to_terrain(settings_, size);
    doc_.context().settings.simplify.tolerance = settings_.simplify_tolerance;
    cursor_tool_.reset();  // built for the old terrain
    haptic_tool_.reset();
    if (k == 1.0) return {};
    char text[160];
    std::snprintf(text, sizeof(text),
                  "tool size, depth, brush, pour, r_S and simplification scaled "
                  "x%.3g for this %.4g m terrain",
                  k, size);
    return text;
}

void App::set_scene_field(const std::string& path) {
    if (path.size() >= sizeof(path_buf_))
        throw std::runtime_error("the path is longer than the Scene field holds");
    std::snprintf(path_buf_, sizeof(path_buf_), "%s", path.c_str());
}

void App::set_export_field(const std::string& path) {
    if (path.size() >= sizeof(export_buf_))
        throw std::runtime_error("the path is longer than the Export path field holds");
    std::snprintf(export_buf_, sizeof(export_buf_), "%s", path.c_str());
}

void App::set_import_field(const std::string& path) {
    if (path.size() >= sizeof(import_buf_))
        throw std::runtime_error("the path is longer than the Heightmap field holds");
    std::snprintf(import_buf_, sizeof(import_buf_), "%s", path.c_str());
}

}  // namespace sandtin::editor
