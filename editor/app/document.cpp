#include "document.hpp"

#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "default_sandbox.hpp"
#include "io/heightmap_import.hpp"
#include "io/import_grid.hpp"
#include "io/session_name.hpp"
#include "io/session_terrain.hpp"
#include "physics/sand_physics.hpp"

namespace sandtin::editor {

// ---- Making one ---------------------------------------------------------------------------

Document Document::make(Tin t, Generation next_generation, const std::filesystem::path& p,
                        MaterialTable table, std::string metadata) {
    Document d;
    d.materials_ = std::move(table);
    d.metadata_json_ = std::move(metadata);
    d.tin_ = std::make_unique<Tin>(std::move(t));
    d.context_ = std::make_unique<SculptContext>(d.tin_->domain());
    d.context_->set_next_generation(next_generation);
    // The editor's consumers (the render mesh, the mirror, the normal map) read the journal
    // through readers of their own: a default reader nobody takes would keep every dead id.
    d.tin_->set_track_changes(false);
    d.solver_ = std::make_unique<SandPhysics>(*d.tin_, d.materials_);
    d.history_ = std::make_unique<History>(*d.tin_);
    d.water_ = std::make_unique<LiveWater>(*d.tin_);
    // Copied whole here, on the thread that builds the document (the worker of Open, Import,
    // Recover and New): the frame then pays only for its edits when an autosave is due.
    d.autosave_copy_ = std::make_unique<SessionKeeper>(*d.tin_);
    d.path_ = p;
    return d;
}

Document Document::sandbox() {
    return make(default_sandbox(), 1, {}, MaterialTable::presets(), "{}");
}

Document Document::placeholder() {
    // Not held: there is nothing on it to slide, and nothing to say about erosion.
    return make(Tin::flat_rectangle(Rect{{0.0, 0.0}, {1.0, 1.0}}), 1, {}, MaterialTable::presets(),
                "{}");
}

Document Document::open(const std::filesystem::path& path, const ProgressCallback& progress) {
    // Shares measured on a large scene: decoding the file and building the TIN (its
    // triangulation checked) about equally, setting up the solver and the history the rest.
    if (progress) progress({0.0, "reading the scene"});
    Session s = load_session(path);
    if (progress) progress({0.45, "building the terrain"});
    Tin tin = take_session_terrain(s, path);
    if (progress) progress({0.85, "setting up the solver and the history"});
    Document d = make(std::move(tin), s.next_generation, path,
                      materials_or_presets(s.metadata_json), s.metadata_json);
    d.erosion_held_ = true;
    if (progress) progress({1.0, "done"});
    return d;
}

Document Document::imported(const std::filesystem::path& heightmap,
                            const ProgressCallback& progress) {
    ImportResult r = import_heightmap(heightmap, ImportOptions{}, progress_part(progress, 0, 0.9));
    if (progress) progress({0.9, "setting up the solver and the history"});
    // The import record, as `sandtin import` writes it.
    Document d = make(std::move(r.tin), 1, {}, MaterialTable::presets(),
                      nlohmann::json{{"import", to_json(r.report)}}.dump());
    d.erosion_held_ = true;
    d.dirty_ = true;  // on no disk yet
    if (progress) progress({1.0, "done"});
    return d;
}

Document Document::recovered(const std::filesystem::path& scene, const ProgressCallback& progress) {
    // The stages and shares of open().
    if (progress) progress({0.0, "reading the autosave"});
    Session s = recover_autosave(scene);
    if (progress) progress({0.45, "building the terrain"});
    Tin tin = Tin::from_snapshot(std::move(s.terrain));
    if (progress) progress({0.85, "setting up the solver and the history"});
    Document d = make(std::move(tin), s.next_generation, scene,
                      materials_or_presets(s.metadata_json), s.metadata_json);
    d.erosion_held_ = true;
    d.dirty_ = true;  // the scene's file does not hold these edits
    if (progress) progress({1.0, "done"});
    return d;
}

Document::Document(Document&& o) noexcept
    : path_(std::move(o.path_)),
      tin_(std::move(o.tin_)),
      context_(std::move(o.context_)),
      solver_(std::move(o.solver_)),
      history_(std::move(o.history_)),
      water_(std::move(o.water_)),
      autosave_copy_(std::move(o.autosave_copy_)),
      undo_log_(std::move(o.undo_log_)),
      materials_(std::move(o.materials_)),
      materials_version_(o.materials_version_),
      metadata_json_(std::move(o.metadata_json_)),
      dirty_(o.dirty_),
      erosion_held_(o.erosion_held_),
      autosave_schedule_(o.autosave_schedule_) {}

Document& Document::operator=(Document&& o) noexcept {
    if (this == &o) return *this;
    close();
    path_ = std::move(o.path_);
    tin_ = std::move(o.tin_);
    context_ = std::move(o.context_);
    solver_ = std::move(o.solver_);
    history_ = std::move(o.history_);
    water_ = std::move(o.water_);
    autosave_copy_ = std::move(o.autosave_copy_);
    undo_log_ = std::move(o.undo_log_);
    materials_ = std::move(o.materials_);
    // Views compare versions: a new document's table is new to them, whatever its count.
    materials_version_ = o.materials_version_ + materials_version_ + 1;
    metadata_json_ = std::move(o.metadata_json_);
    dirty_ = o.dirty_;
    erosion_held_ = o.erosion_held_;
    autosave_schedule_ = o.autosave_schedule_;
    return *this;
}

Document::~Document() {
    close();
}

void Document::close() {
    autosave_copy_.reset();
    water_.reset();
    history_.reset();
    solver_.reset();
    context_.reset();
    tin_.reset();
}

void Document::replace_solver(
    const std::function<std::unique_ptr<RelaxationSolver>(Tin&)>& make_solver) {
    solver_.reset();  // the old one lets go of the TIN (and its GPU objects) first
    solver_ = make_solver(*tin_);
}

// ---- Undo ---------------------------------------------------------------------------------

void Document::record_level(const std::string& label) {
    if (history_->record(label)) {
        undo_log_.push_terrain(label);
        mark_edited(std::chrono::steady_clock::now());
    }
}

UndoOutcome Document::undo() {
    return step_back_or_forward(true);
}

UndoOutcome Document::redo() {
    return step_back_or_forward(false);
}

UndoOutcome Document::step_back_or_forward(bool back) {
    const std::string verb = back ? "undo" : "redo";
    UndoOutcome out;
    const std::optional<UndoLog::Entry> entry = back ? undo_log_.undo() : undo_log_.redo();
    if (!entry) {
        out.message = "nothing to " + verb;
        return out;
    }
    out.done = true;
    mark_edited(std::chrono::steady_clock::now());
    if (!entry->terrain) {
        apply_materials(back ? entry->before : entry->after);
        out.message = verb + " " + entry->label;
        return out;
    }
    const HistoryStep step = back ? history_->undo() : history_->redo();
    out.done = step.done;
    out.message = step.done ? verb + " " + step.label : "nothing to " + verb;
    if (step.done && !step.report.exact()) {
        out.message += " (approximate: " + std::to_string(step.report.unrestored.size()) +
                       " vertices could not be restored)";
    }
    // Undoing the erosion's own level puts back sand that would slide again at once.
    out.restored_erosion = back && step.done && step.label == kErosionLevel;
    return out;
}

void Document::apply_materials(MaterialTable table) {
    materials_ = std::move(table);
    ++materials_version_;
    // The solver re-reads the angles of repose and looks at every vertex again.
    solver_->set_materials(materials_);
}

void Document::edit_material(int index, const Material& material) {
    std::vector<Material> all = materials_.all();
    if (index < 0 || index >= static_cast<int>(all.size()))
        throw std::runtime_error("there is no material " + std::to_string(index));
    all[static_cast<std::size_t>(index)] = material;
    const MaterialTable before = materials_;
    apply_materials(MaterialTable(std::move(all)));
    undo_log_.push_materials(before, materials_);
    mark_edited(std::chrono::steady_clock::now());
}

// ---- Files --------------------------------------------------------------------------------

Session Document::session() const {
    Session s;
    s.terrain = tin_->snapshot();
    s.next_generation = context_->peek_generation();
    s.metadata_json = session_metadata(materials_, metadata_json_);
    return s;
}

std::optional<std::string> Document::save_name_problem(const std::filesystem::path& path) {
    // The rule `sandtin` applies to its -o: a session never takes another format's name (the
    // document would then carry that name, and Ctrl+S write there again).
    if (const std::optional<std::string> problem = session_name_problem(path))
        return "'" + path.string() + "': " + *problem + " (Export writes meshes and maps)";
    return std::nullopt;
}

void Document::save(const std::filesystem::path& path) {
    if (const std::optional<std::string> problem = save_name_problem(path))
        throw std::runtime_error(*problem);
    save_session_clearing_autosave(path, session());
    saved_as(path);
}

void Document::saved_as(const std::filesystem::path& path) {
    path_ = path;
    dirty_ = false;
    autosave_schedule_.saved(std::chrono::steady_clock::now());
}

ExportOptions Document::export_options() const {
    // The defaults `sandtin export` takes from the session: the import grid while the terrain
    // lies on it, and the georeference; the colours are the live table's.
    ExportOptions options;
    apply_import_defaults(*tin_, metadata_json_, options);
    options.palette = export_palette(materials_);
    return options;
}

ExportReport Document::export_to(const std::filesystem::path& path,
                                 const ProgressCallback& progress) const {
    return export_terrain(*tin_, path, export_format_for(path), export_options(), progress);
}

void Document::mark_edited(std::chrono::steady_clock::time_point now) {
    dirty_ = true;
    autosave_schedule_.edited(now);
}

void Document::autosave_if_due(AutosaveWriter& writer, std::chrono::steady_clock::time_point now) {
    if (path_.empty() || !autosave_schedule_.due(now)) return;
    writer.submit(path_, autosave_source());
    autosave_schedule_.saved(now);
}

bool Document::keep_in_autosave(AutosaveWriter& writer) {
    if (!dirty_ || path_.empty()) return false;
    writer.submit(path_, autosave_source());
    return true;
}

SessionSource Document::autosave_source() {
    return autosave_copy_->hand_out(context_->peek_generation(),
                                    session_metadata(materials_, metadata_json_));
}

void Document::follow_edits_for_autosave() {
    if (autosave_copy_) autosave_copy_->follow();
}

}  // namespace sandtin::editor
