#pragma once
// One scene being edited: its terrain, sculpting context, solver, undo history and material
// table, and where it is saved. Everything here follows the scene's lifetime, and nothing here
// draws or asks: the GPU's views of the terrain (terrain_view.hpp) and the panels read it, and
// the app decides when to call its operations (after a prompt, on a shortcut or a button).
//
// Document operations: make one (a new sandbox, a file, a heightmap, an autosave), save it,
// export it, undo and redo, edit its materials. A Document is movable: its parts live on the
// heap, so the history's and the solver's references to the TIN stay valid.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "history/history.hpp"
#include "io/autosave.hpp"
#include "io/autosave_writer.hpp"
#include "io/export_terrain.hpp"
#include "io/progress.hpp"
#include "io/scene_materials.hpp"
#include "io/session_file.hpp"
#include "io/session_keeper.hpp"
#include "physics/terrain_solver.hpp"
#include "tools/sculpt_context.hpp"
#include "undo_log.hpp"
#include "water/live_water.hpp"

namespace sandtin::editor {

/// What an undo or redo did, for the status line.
struct UndoOutcome {
    bool done = false;
    std::string message;  ///< "undo stroke (Ball)", "nothing to undo", ...
    /// The level was erosion alone: what it restored is not at rest, and erosion running on
    /// would slide it straight back (the caller pauses it).
    bool restored_erosion = false;
};

class Document {
  public:
    /// The undo level of sand the erosion moved with no gesture of the artist's before it.
    static constexpr const char* kErosionLevel = "erosion";

    /// A new 1 m sandbox (default_sandbox()), untitled; it erodes once sculpted.
    static Document sandbox();
    /// A flat 1 m square of two triangles, untitled: what the window shows behind the
    /// progress bar while the scene named on the command line is read (cheap to show: the
    /// sandbox took 160-230 ms of a frame to install on a CPU renderer).
    static Document placeholder();
    /// The session at `path`, with its material table; held (erosion waits for Run). Throws
    /// on a file that does not load, before anything else is touched. `progress`
    /// (io/progress.hpp) hears reading, the terrain's build and the document's set-up; it may
    /// throw (Cancelled) to stop there. Touches nothing shared: runs on a worker thread.
    static Document open(const std::filesystem::path& path, const ProgressCallback& progress = {});
    /// A heightmap meshed as `sandtin import` meshes it: untitled, unsaved and held, with the
    /// import record in its metadata (exports read its grid and georeference). `progress` as
    /// for open().
    static Document imported(const std::filesystem::path& heightmap,
                             const ProgressCallback& progress = {});
    /// The autosave of the scene at `scene`, as that scene (edited since it was saved); held.
    /// `progress` as open()'s; it touches nothing shared either.
    static Document recovered(const std::filesystem::path& scene,
                              const ProgressCallback& progress = {});

    Document() = default;
    Document(Document&&) noexcept;
    /// Tears this document down first, in the order its parts depend on each other.
    Document& operator=(Document&& other) noexcept;
    ~Document();
    Document(const Document&) = delete;
    Document& operator=(const Document&) = delete;

    // ---- State ---------------------------------------------------------------------------
    /// False only for a default-constructed (empty) document.
    bool has_terrain() const { return tin_ != nullptr; }
    const std::filesystem::path& path() const { return path_; }
    bool untitled() const { return path_.empty(); }
    /// Edits not yet saved to the scene's file.
    bool dirty() const { return dirty_; }
    /// An opened, imported or recovered terrain is not eroded until the artist presses Run (an
    /// elevation model would otherwise start melting as it appears).
    bool erosion_held() const { return erosion_held_; }
    void release_erosion() { erosion_held_ = false; }

    Tin& tin() { return *tin_; }
    const Tin& tin() const { return *tin_; }
    SculptContext& context() { return *context_; }
    RelaxationSolver& solver() { return *solver_; }
    const RelaxationSolver& solver() const { return *solver_; }
    /// Destroys the solver ahead of the document (it may relax on a mirror that must go before
    /// the TIN does); solver() is invalid until replace_solver().
    void drop_solver() { solver_.reset(); }
    /// Replaces the solver (the Erosion panel's CPU/GPU switch); the old one goes first.
    void replace_solver(const std::function<std::unique_ptr<RelaxationSolver>(Tin&)>& make);
    /// The water running over the terrain (the Water tool, rain); its depths are the TIN's.
    LiveWater& water() { return *water_; }
    const LiveWater& water() const { return *water_; }
    const History& history() const { return *history_; }
    const UndoLog& undo_log() const { return undo_log_; }
    const MaterialTable& materials() const { return materials_; }
    /// Bumped whenever the material table changes (an edit, its undo): views that colour
    /// the terrain by it rebuild then.
    std::uint64_t materials_version() const { return materials_version_; }
    const std::string& metadata() const { return metadata_json_; }

    // ---- Operations ----------------------------------------------------------------------
    /// The edits since the last level become one undo level named `label` (nothing when the
    /// terrain did not change); the document is then dirty.
    void record_level(const std::string& label);
    UndoOutcome undo();
    UndoOutcome redo();
    /// The Materials panel's edit of material `index` (throws for an index the table lacks):
    /// one undo level. Every vertex is looked at again by the solver.
    void edit_material(int index, const Material& material);

    /// Writes the scene to `path` atomically and makes it the scene's file: not under another
    /// format's name (a .png, an .obj), and its autosave goes. Throws naming the problem.
    void save(const std::filesystem::path& path);
    /// What save() refuses before writing anything (another format's name), or nothing.
    static std::optional<std::string> save_name_problem(const std::filesystem::path& path);
    /// After the session() taken for `path` was written there (by a worker, App::save): the
    /// scene's file is `path`, with nothing unsaved.
    void saved_as(const std::filesystem::path& path);
    /// The terrain as `sandtin export` writes it (format from the extension), with the
    /// materials as they are now, unsaved edits included. Throws on failure; `progress` may
    /// throw (Cancelled), and the export then writes nothing. Only reads the document: a worker
    /// thread may run it while nothing edits the document (App::export_reporting).
    ExportReport export_to(const std::filesystem::path& path,
                           const ProgressCallback& progress = {}) const;
    /// The session a save or an autosave writes.
    Session session() const;
    /// Edits were made: the scene needs saving, and an autosave once the interval passed.
    void mark_edited(std::chrono::steady_clock::time_point now);
    /// Submits an autosave to `writer` when one is due (a scene with a file, edited a minute
    /// ago); `now` the caller's clock.
    void autosave_if_due(AutosaveWriter& writer, std::chrono::steady_clock::time_point now);
    /// Unsaved edits of a scene with a file go to its autosave now (closing, replacing it).
    /// True when something was submitted.
    bool keep_in_autosave(AutosaveWriter& writer);
    /// Brings the copy autosaves are made from up to the terrain: what this frame's edits
    /// touched. Once a frame, after the edits.
    void follow_edits_for_autosave();

  private:
    /// The options `sandtin export` would take from this scene (export_to).
    ExportOptions export_options() const;
    /// Undo (`back`) or redo: a material edit or a terrain level of the history.
    UndoOutcome step_back_or_forward(bool back);
    static Document make(Tin t, Generation next_generation, const std::filesystem::path& p,
                         MaterialTable table, std::string metadata);
    void apply_materials(MaterialTable table);
    /// Drops the parts that refer to the TIN before the TIN.
    void close();
    /// The session an autosave writes, made on the writer's thread from the kept copy.
    SessionSource autosave_source();

    std::filesystem::path path_;
    std::unique_ptr<Tin> tin_;
    std::unique_ptr<SculptContext> context_;
    std::unique_ptr<RelaxationSolver> solver_;
    std::unique_ptr<History> history_;
    std::unique_ptr<LiveWater> water_;
    /// The copy autosaves are made from (io/session_keeper.hpp), followed once a frame.
    std::unique_ptr<SessionKeeper> autosave_copy_;
    UndoLog undo_log_;  ///< terrain levels (history_) and material edits, in order
    MaterialTable materials_ = MaterialTable::presets();
    std::uint64_t materials_version_ = 0;
    /// The metadata the terrain came with (an import record, another tool's keys); saves keep
    /// it, with the materials replaced.
    std::string metadata_json_ = "{}";
    bool dirty_ = false;
    bool erosion_held_ = false;
    AutosaveSchedule autosave_schedule_{std::chrono::seconds(60)};
};

}  // namespace sandtin::editor
