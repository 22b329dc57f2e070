// Document operations: the one path by which a document replaces another, New, Open, Import,
// Recover, Save (with its overwrite guard), Export, undo and redo, and the autosave.

#include "app.hpp"
#include "io/session_name.hpp"

namespace sandtin::editor {

namespace {

/// Whether `a` and `b` name the same file (either may not exist yet).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec;
    return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

/// A scene name for an imported heightmap: beside it, with its stem, and not taken by a file
/// or an autosave ("bay-hills.sandtin", else "bay-hills-2.sandtin", ...).
std::filesystem::path scene_name_for_import(const std::filesystem::path& heightmap) {
    const std::filesystem::path folder = heightmap.parent_path();
    const std::string stem = heightmap.stem().string();
    for (int n = 1; n < 1000; ++n) {
        const std::string name = n == 1 ? stem : stem + "-" + std::to_string(n);
        const std::filesystem::path candidate = folder / (name + ".sandtin");
        std::error_code ec;
        if (!std::filesystem::exists(candidate, ec) && !find_autosave(candidate)) return candidate;
    }
    return folder / (stem + "-imported.sandtin");
}

}  // namespace

// ---- Replacing the document ---------------------------------------------------------------

void App::install_document(Document next, const std::string& message) {
    // What the old document had under way ends with it (its open undo level included).
    if (doc_.tin) end_action();
    // Nothing a submitted frame or solver step may still read is destroyed before the GPU is
    // done with it; then every object built for the old terrain goes, the GPU physics (and
    // its mirror) with the old document.
    wait_gpu_idle();
    normal_map_.reset();
    own_mirror_.reset();
    doc_ = std::move(next);
    mesh_ = std::make_unique<render::TerrainMesh>(doc_.materials);
    renderer_->drop_mesh();
    fanout_ = std::make_unique<ChangeFanout>(*doc_.tin);
    undo_log_.clear();
    open_level_.clear();
    resettling_ = false;
    sampler_.reset();
    active_tool_.reset();
    pour_flow_.reset();
    last_dab_.reset();
    cursor_.reset();
    active_.clear();
    active_ids_.clear();
    active_flipped_.clear();
    erosion_active_ = 0;
    const std::string scaled = fit_settings_to_document();
    // The material the Paint brush and the pour use must be in this document's table.
    settings_.material =
        std::clamp(settings_.material, 0, static_cast<int>(doc_.materials.size()) - 1);
    // A new document starts clean (a recovered one is already on disk as the autosave).
    autosave_schedule_.saved(Clock::now());
    attach_physics(false);
    // An opened scene was never relaxed by this physics (it may have been saved mid-slide,
    // or imported steeper than repose): all of it is a candidate, as after a switch of
    // solver. What is at rest leaves the active set after a few quiet iterations.
    doc_.physics->activate_all();
    physics_kick_ = true;
    mesh_stale_ = true;
    contrast_stale_ = true;
    // The mesh, the mirror and the normal map of the new terrain exist before anything draws,
    // even when this runs between a panel's button and the end of its frame.
    update_mesh();
    frame_terrain();
    std::string text = message;
    if (!scaled.empty()) text += text.empty() ? scaled : "; " + scaled;
    if (doc_.erosion_held && settings_.erosion_running)
        text += std::string(text.empty() ? "" : "; ") + "erosion waits for Run";
    if (!text.empty()) report(text);
}

void App::new_document() {
    keep_unsaved_edits();
    install_document(Document::make(default_sandbox(), 1, {}), "new sandbox");
}

void App::open(const std::filesystem::path& p) {
    end_action();
    // Read before anything is dropped: a file that does not load leaves the scene as it was.
    const Session s = load_session(p);
    Document next = Document::make(session_terrain(s, p), s.next_generation, p,
                                   materials_or_presets(s.metadata_json), s.metadata_json);
    next.erosion_held = true;
    keep_unsaved_edits();
    install_document(std::move(next), "opened " + p.string());
}

void App::open_reporting() {
    try {
        open(path_buf_);
    } catch (const std::exception& e) {
        report(std::string("open failed: ") + e.what());
    }
}

void App::import_document() {
    try {
        const std::filesystem::path heightmap = import_buf_;
        ImportResult r = import_heightmap(heightmap, ImportOptions{});
        // The import record, as `sandtin import` writes it: exports read its grid and
        // georeference. An imported model is a scene of its own: untitled, unsaved, and with a
        // name of its own in the Scene field, so Save never writes it over the scene it
        // replaced.
        Document next = Document::make(std::move(r.tin), 1, {}, MaterialTable::presets(),
                                       nlohmann::json{{"import", to_json(r.report)}}.dump());
        next.erosion_held = true;
        next.dirty = true;
        keep_unsaved_edits();
        const std::filesystem::path name = scene_name_for_import(heightmap);
        set_scene_field(name.string());
        install_document(std::move(next), "imported " + heightmap.string() +
                                              " (untitled: Save writes " + name.string() + ")");
    } catch (const std::exception& e) {
        report(std::string("import failed: ") + e.what());
    }
}

void App::answer_recovery(bool recover) {
    if (!recovery_for_) throw std::runtime_error("there is no autosave to recover or discard");
    const std::filesystem::path scene = *recovery_for_;
    recovery_for_.reset();
    autosave_writer_.cancel();  // nothing may rewrite the autosave being recovered or discarded
    // The autosave was checked when the scene opened, but it can still fail now (its terrain
    // may not rebuild, the folder may have become read-only): the scene stays as it is.
    try {
        if (recover) {
            const Session s = recover_autosave(scene);
            Document next = Document::make(Tin::from_snapshot(s.terrain), s.next_generation, scene,
                                           materials_or_presets(s.metadata_json), s.metadata_json);
            next.erosion_held = true;
            install_document(std::move(next), "recovered the autosave of " + scene.string());
            mark_edited();
        } else {
            discard_autosave(scene);
            report("discarded the autosave of " + scene.string());
        }
    } catch (const std::exception& e) {
        report(std::string(recover ? "cannot recover the autosave: " : "cannot discard it: ") +
               e.what());
    }
}

void App::replace_document(const std::string& what, std::function<void()> action) {
    end_action();
    if (doc_.dirty && doc_.path.empty()) {
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
    if (!glfwWindowShouldClose(window_)) return false;
    if (quit_confirmed_ || !doc_.dirty || !doc_.path.empty()) return true;
    // Closing would drop an untitled scene's edits: stay open and ask (discard_prompt).
    glfwSetWindowShouldClose(window_, GLFW_FALSE);
    replace_document("Quit", [this] {
        quit_confirmed_ = true;
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
    });
    redraw_frames_ = 3;
    return false;
}

// ---- Saving -------------------------------------------------------------------------------

void App::save(const std::filesystem::path& p) {
    // The rule `sandtin` applies to its -o: a session never takes another format's name (the
    // document would then carry that name, and Ctrl+S write there again).
    if (const std::optional<std::string> problem = session_name_problem(p))
        throw std::runtime_error("'" + p.string() + "': " + *problem +
                                 " (Export writes meshes and maps)");
    end_action();
    // An autosave still being written would otherwise land after the save retired it.
    autosave_writer_.cancel();
    save_session_clearing_autosave(p, doc_.session());
    doc_.path = p;
    doc_.dirty = false;
    autosave_schedule_.saved(Clock::now());
    set_scene_field(p.string());
    report("saved " + p.string());
}

bool App::save_reporting(const std::filesystem::path& p) {
    try {
        save(p);
        return true;
    } catch (const std::exception& e) {
        report(std::string("save failed: ") + e.what());
        return false;
    }
}

void App::request_save(const std::filesystem::path& p, std::function<void()> then) {
    end_action();
    std::error_code ec;
    const bool own_file = !doc_.path.empty() && same_file(p, doc_.path);
    // Another scene's file, or the autosave that keeps another scene's unsaved edits, is
    // replaced only when the artist says so.
    if (!own_file && (std::filesystem::exists(p, ec) || find_autosave(p))) {
        pending_overwrite_ = PendingOverwrite{p, std::move(then)};
        return;
    }
    if (save_reporting(p) && then) then();
}

void App::export_to(const std::filesystem::path& p) {
    end_action();
    // The defaults `sandtin export` takes from the session: the import grid while the terrain
    // lies on it, and the georeference; the colours are the live table's, unsaved edits included.
    ExportOptions options;
    apply_import_defaults(*doc_.tin, doc_.metadata_json, options);
    options.palette = export_palette(doc_.materials);
    const ExportReport r = export_terrain(*doc_.tin, p, export_format_for(p), options);
    report("exported " + std::to_string(r.files.size()) + " file(s)");
}

void App::keep_unsaved_edits() {
    if (doc_.dirty && !doc_.path.empty() && autosaves()) {
        autosave_writer_.submit(doc_.path, doc_.session());
        report("unsaved edits of " + doc_.path.string() + " kept in its autosave");
    }
    autosave_writer_.flush();
    if (const std::optional<std::string> error = autosave_writer_.take_error())
        report("autosave failed: " + *error);
}

void App::autosave_if_due() {
    const auto now = Clock::now();
    if (const std::optional<std::string> error = autosave_writer_.take_error()) {
        report("autosave failed, will retry: " + *error);
        autosave_schedule_.edited(now);  // due again one interval from now
    }
    if (doc_.path.empty() || !autosaves() || !autosave_schedule_.due(now)) return;
    autosave_writer_.submit(doc_.path, doc_.session());
    autosave_schedule_.saved(now);
}

// ---- View and settings that follow the document -------------------------------------------

void App::frame_terrain() {
    const Rect d = doc_.tin->domain();
    const VertexArrays& va = doc_.tin->vertices();
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        lo = std::min(lo, va.height[i]);
        hi = std::max(hi, va.height[i]);
    }
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    // The whole terrain where the panel does not cover it; in a window too narrow for that,
    // the whole terrain in the whole view.
    camera_.frame_in({-0.5 * d.width(), -0.5 * d.height(), lo},
                     {0.5 * d.width(), 0.5 * d.height(), hi}, w, h, free_viewport(w, h));
}

std::string App::fit_settings_to_document() {
    const double size = terrain_size(doc_.tin->domain());
    const double k = fit_settings_to_terrain(settings_, size);
    doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance;
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

// ---- Undo, redo and material edits --------------------------------------------------------

void App::apply_materials(const MaterialTable& table) {
    doc_.materials = table;
    // Both solvers re-read the angles of repose and look at every vertex again.
    doc_.physics->set_materials(doc_.materials);
    mesh_->set_materials(doc_.materials);
    mesh_stale_ = true;  // colours and slope ratios of every vertex
    physics_kick_ = true;
}

void App::edit_material(int index, const Material& m) {
    std::vector<Material> all = doc_.materials.all();
    if (index < 0 || index >= static_cast<int>(all.size()))
        throw std::runtime_error("there is no material " + std::to_string(index));
    all[static_cast<std::size_t>(index)] = m;
    // The whole terrain is re-checked against the new angles and the colours are rebuilt. One
    // undo level, saved with the scene.
    end_action();
    const MaterialTable before = doc_.materials;
    apply_materials(MaterialTable(std::move(all)));
    undo_log_.push_materials(before, doc_.materials);
    mark_edited();
}

void App::undo() {
    end_action();
    const std::optional<UndoLog::Entry> entry = undo_log_.undo();
    if (!entry) {
        report("nothing to undo");
        return;
    }
    if (!entry->terrain) {
        apply_materials(entry->before);
        report("undo " + entry->label);
        mark_edited();
        return;
    }
    const HistoryStep step = doc_.history->undo();
    std::string message = step.done ? "undo " + step.label : "nothing to undo";
    if (step.done && !step.report.exact()) {
        message += " (approximate: " + std::to_string(step.report.unrestored.size()) +
                   " vertices could not be restored)";
    }
    // A stroke's level holds its settling, so what it restores was at rest and the erosion
    // runs on. A level of erosion alone (Run on a scene steeper than repose, a material made
    // steeper) restores sand that is not at rest: running on, the physics would slide it
    // straight back and undo the undo, so the erosion pauses there, and says so.
    if (step.done && step.label == kErosionLevel && erosion_runs()) {
        settings_.erosion_running = false;
        message += "; erosion paused (Run slides it again)";
    }
    report(message);
    physics_kick_ = true;
    mark_edited();
}

void App::redo() {
    end_action();
    const std::optional<UndoLog::Entry> entry = undo_log_.redo();
    if (!entry) {
        report("nothing to redo");
        return;
    }
    if (!entry->terrain) {
        apply_materials(entry->after);
        report("redo " + entry->label);
        mark_edited();
        return;
    }
    const HistoryStep step = doc_.history->redo();
    report(step.done ? "redo " + step.label : "nothing to redo");
    physics_kick_ = true;
    mark_edited();
}

}  // namespace sandtin::editor
