#pragma once
// The editor application: a UI over a document. App keeps the window, the input and the
// panels; the scene and its operations are the Document's (document.hpp), an edit from the
// button going down to the sand coming to rest is Sculpting's (sculpting.hpp), and the
// terrain's GPU views are TerrainView's (terrain_view.hpp). Its member functions are spread
// over app_*.cpp and panel_*.cpp by concern:
//   app.cpp          set-up, the loops, the stats and outputs of a scripted run
//   app_document.cpp the document commands: the prompts that guard them, install_document
//   app_files.cpp    files handed over without a field: dropped, or picked from the recent list
//   app_file_dialogs.cpp  Open..., Save As..., Import..., Export...: the desktop's dialog or
//                    the editor's own browser (panel_file_browser.cpp draws it)
//   app_jobs.cpp     long work: import, open and export on a worker; the erosion to rest
//   app_input.cpp    mouse and keys: the camera, the tools, shortcuts
//   app_frame.cpp    one frame: erosion, the terrain's views, drawing
//   app_script.cpp   scripted mode: ops as real input
//   panel_*.cpp      the ImGui panels and prompts, as plain functions of the state

#include <imgui.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "background_job.hpp"
#include "camera.hpp"
#include "document.hpp"
#include "editor_app.hpp"
#include "editor_settings.hpp"
#include "editor_window.hpp"
#include "file_browser.hpp"
#include "file_dialog_request.hpp"
#include "file_kinds.hpp"
#include "frame_policy.hpp"
#include "haptics_session.hpp"
#include "layout_probe.hpp"
#include "native_file_dialog.hpp"
#include "sculpting.hpp"
#include "settle_progress.hpp"
#include "shortcuts.hpp"
#include "stage_times.hpp"
#include "terrain_view.hpp"
#include "util/elapsed_ms.hpp"
#include "widget_map.hpp"
#include "x_input.hpp"

namespace sandtin::editor {

using Clock = std::chrono::steady_clock;

/// Milliseconds of relaxation per frame at most (the rest waits for the next frame).
inline constexpr double kErosionBudgetMs = 25.0;
/// Milliseconds of water per frame at most: the water falls behind real time beyond it.
inline constexpr double kWaterBudgetMs = 15.0;

/// Seconds a frame of a scripted run counts for (a held pour): 60 frames a second, so a
/// script pours the same on any machine, however fast it draws.
inline constexpr double kScriptFrameSeconds = 1.0 / 60.0;

/// Installs the window's GLFW callbacks, which route to the App in its user pointer.
void install_callbacks(GLFWwindow* window);

class App {
  public:
    explicit App(const EditorOptions& o) : options_(o) {}
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;
    int run();

    // ---- What the window's callbacks call (app_input.cpp) --------------------------------
    /// Every callback calls this first: the loop's timed waits tell events from timeouts, the
    /// haptic snapshot is no longer held (the event may edit the terrain), and ImGui gets the
    /// frames it needs to settle.
    void note_event();
    /// Whether a press or the wheel at (x, y) is the panels' and not the terrain's: a prompt
    /// is open, or the point lies on a window the last frame drew. (ImGui's WantCaptureMouse
    /// is where the pointer was when the last frame began: a press that follows the click
    /// closing a prompt, or the pointer moving off a panel, before the next frame would be
    /// judged by where it was.)
    bool ui_takes_pointer(double x, double y) const {
        return prompt_open() || busy() || widgets_.covers(x, y);
    }
    void mouse_button(int button, bool down, double x, double y);
    void mouse_move(double x, double y);
    void scroll(double dy);
    void key(int key, bool ctrl);
    /// Files dropped on the window (app_files.cpp): the first is opened or imported as its
    /// kind says, behind the unsaved-edits prompt; anything else is refused with a message.
    void drop_files(const std::vector<std::string>& paths);
    /// Runs an input handler; an error in it (a tool that refuses its parameters, a file that
    /// cannot be read) is shown on the status line and the gesture under way is ended, never
    /// thrown through GLFW (C code) or out of the editor.
    template <class F>
    void guarded(const char* what, F&& handler) {
        try {
            handler();
        } catch (const std::exception& e) {
            sculpting_.abandon(doc_);
            report(std::string(what) + ": " + e.what());
        }
    }

  private:
    // ---- Set-up and the loops (app.cpp) --------------------------------------------------
    void load_settings_reporting();
    /// What the window shows first: the sandbox, or with a scene named on the command line a
    /// placeholder while start_opening_initial_scene() reads it.
    Document initial_document();
    /// Opens the command line's scene as Open does, on a worker behind the progress bar.
    void start_opening_initial_scene();
    /// The command line's scene did not open: a scripted run fails, an artist gets the sandbox.
    void initial_scene_failed(const std::string& problem);
    void interactive_loop();
    void scripted_loop();
    void idle_measurement(std::uint64_t& submissions, std::uint64_t& gpu_work);
    void write_stats(std::uint64_t idle_submissions, std::uint64_t idle_gpu_work);
    /// A scripted run's outputs, data first: the scene (--save-after), then the screenshot.
    /// Each is tried whatever became of the other; the failures are returned, for the run to
    /// report and exit 1 with.
    std::vector<std::string> write_outputs();
    /// Writes the widget map to --widget-map when it changed (the xdotool test reads it).
    void publish_widget_map();
    LoopState loop_state() const;
    /// Waits as frame_policy.hpp decides for `state`, for at most `at_most_seconds` when that
    /// is not kWaitForEvent, and says whether to draw a frame now.
    bool wait_for_events(const LoopState& state, double at_most_seconds);
    /// Writes the settings file after a change; a failure is reported, not thrown.
    void save_settings_reporting();
    void report(const std::string& message);
    /// Every piece of GPU work so far: frames submitted, normal-map bakes, mirror upload
    /// batches and relaxation dispatches. An idle editor adds nothing to it.
    std::uint64_t gpu_work();

    // ---- Document commands (app_document.cpp) --------------------------------------------
    /// The one way a document replaces another (New, Open, Import, Recover, and the scene at
    /// start-up): what the old one had under way ends, and everything that follows the
    /// terrain is built again for the new one (its GPU views, the solver, the gesture state)
    /// before anything draws, wherever this is called from.
    void install_document(Document next, const std::string& message);
    /// The same for a document read on a worker with its view prepared there (app_jobs.cpp):
    /// the UI thread's share is the GPU's, not the CPU's O(n) builds.
    void install_document(PreparedDocument next, const std::string& message);
    void install(Document next, std::optional<PreparedView> prepared, const std::string& message);
    /// Replaces the document (New, Open, Import) through `action`; when that would drop the
    /// unsaved edits of an untitled scene (no file, so no autosave to keep them), the user is
    /// asked first. A scene with a file keeps its edits in the autosave (keep_unsaved_edits).
    void replace_document(const std::string& what, std::function<void()> action);
    enum class DiscardChoice { Save, Discard, Cancel };
    /// The discard prompt's answer. Save writes the scene where Save and Ctrl+S write an
    /// untitled one (the File panel's Scene field), then goes on.
    void answer_discard(DiscardChoice choice);
    /// The recovery prompt's answer.
    void answer_recovery(bool recover);
    /// Asks about `scene`'s autosave (the recovery prompt) when one newer than it exists.
    void offer_recovery_of(const std::filesystem::path& scene);
    /// The window was asked to close and may: an untitled scene with unsaved edits asks
    /// first (the discard prompt), and the window stays open meanwhile.
    bool close_confirmed();
    void new_document();
    /// Opens the scene at `path` (the Scene field's, a recent or a dropped file's) on a worker
    /// (app_jobs.cpp); once read, it replaces the document and goes in the Scene field and the
    /// recent list. A failure or a Cancel is reported and leaves the document as it was.
    void open_reporting(const std::filesystem::path& path);
    /// Imports the heightmap at `path` on a worker as an untitled scene; once read, it fills
    /// the Scene field with a name of its own and notes the heightmap in the recent list
    /// (finish_import). A failure or a Cancel is reported and leaves the document as it was.
    void import_document(const std::filesystem::path& heightmap);
    /// Reads a document on a worker with `read` and prepares its view there too, under the
    /// bar; once done, `install` takes it on the UI thread (Open, Recover, Import, New).
    using ReadDocument = std::function<Document(const ProgressCallback&)>;
    void start_document_job(const std::string& kind, const std::string& title, ReadDocument read,
                            std::function<void(PreparedDocument)> install);
    /// Recovers `scene`'s autosave on a worker, as Open reads a scene (the recovery prompt's
    /// Recover); a failure is reported and leaves the document as it was.
    void recover_document(const std::filesystem::path& scene);
    void finish_import(const std::filesystem::path& heightmap, PreparedDocument next);
    /// A file handed over without a field (dropped, or a recent one): a scene is opened and a
    /// heightmap imported, each as the Open and Import buttons do, behind the unsaved-edits
    /// prompt; anything else is refused on the status line, naming it and what is accepted.
    void open_or_import(const std::filesystem::path& path, FileKind kind);
    /// The File panel's recent list; an entry clicked is opened by open_or_import.
    void recent_files_list();
    /// Save, Save As, Ctrl+S and the prompts' Save: writes the scene to `p`, then runs `then`.
    /// A file at `p` that is not this scene's own is replaced only after the overwrite prompt
    /// says so. A failure is reported on the status line and `then` does not run.
    void request_save(const std::filesystem::path& p, std::function<void()> then = {});
    /// Saves the scene as it is now to `p` (scripts and the overwrite prompt's Replace): the
    /// copy is taken here, encoded and written on a worker under the bar (app_jobs.cpp), then
    /// `then` runs. A failure is reported on the status line and `then` does not run.
    void save(const std::filesystem::path& p, std::function<void()> then = {});
    /// Saves now, on this thread (--save-after, when the run ends); throws.
    void save_now(const std::filesystem::path& p);
    /// Exports a copy of the terrain as it is now, on a worker; a failure or a Cancel is
    /// reported, and a cancelled export writes no file.
    void export_reporting(const std::filesystem::path& p);

    // ---- Long work (app_jobs.cpp) --------------------------------------------------------
    /// A job runs: the terrain, the document commands and saving wait for it.
    bool busy() const { return job_ != nullptr; }
    /// While a job runs: says on the status line that `what` was not done, and returns true.
    bool refuse_while_busy(const std::string& what);
    /// Starts `work` on a worker; `done` takes its result on the UI thread once it is done.
    void start_job(const std::string& kind, const std::string& title, BackgroundJob::Work work,
                   std::function<void()> done);
    /// Every frame: a job that ended is taken (its result installed, its failure or Cancel
    /// reported).
    void poll_job();
    /// The Cancel button and Escape: the job stops at its next check.
    void cancel_job();
    /// The job's bar was drawn showing `shown` (for a scripted run's stats).
    void note_job_shown(const JobProgress& shown);
    /// A frame of erosion: measures the erosion's own settle to rest for its bar.
    void update_settle(const ErosionFrame& e);
    /// The settle bar's Stop: the erosion pauses, and what settled is one undo level.
    void stop_settling();
    /// The Erosion panel's Settle exactly: the sand projected onto its angle of repose on a
    /// worker under the bar (physics/settle_by_projection.hpp), the terrain copied here first
    /// and the heights written here once it is done, as one undo level. Cancel leaves the
    /// terrain as it was. With Fit toe and crest, the projection's bends get vertices on the
    /// surface as it was and a second projection follows (start_settle_projection).
    void settle_exactly();
    /// One projection of Settle exactly on a worker. `fit_rounds` rounds of fitting the
    /// settled surface's bends follow it before a projection is applied
    /// (physics/settle_fitted_to_kinks.hpp); `fitted` vertices were put on bends already.
    void start_settle_projection(int fit_rounds, std::size_t fitted);
    /// Where Save and Ctrl+S write: the scene's file, or the Scene field for an untitled one.
    std::filesystem::path save_path() const {
        return doc_.untitled() ? std::filesystem::path(path_buf_) : doc_.path();
    }
    void undo();
    void redo();
    /// The Materials panel's edit of material `index` (released control): an undo level.
    void edit_material(int index, const Material& m);
    /// Autosaves a document with unsaved edits a minute after the first of them (copied and
    /// written on the writer's thread: the frame only hands over its kept copy), and shows a
    /// failed write.
    void autosave_if_due();
    /// Before the editor closes (or a script asks): unsaved edits of a scene with a file go to
    /// its autosave, which is offered for recovery when the scene is opened again, and the write
    /// is waited for and its failure shown.
    void keep_unsaved_edits();
    /// Before the document is replaced: the same, without waiting for the write (a 10^6-vertex
    /// one takes 0.4 s); a failure shows at the next frame's autosave_if_due.
    void hand_unsaved_edits_to_autosave();
    void frame_terrain();
    /// The length settings follow the new document's terrain size (terrain_scale.hpp), and the
    /// document's sculpting context takes the panel's simplification tolerance. Returns the
    /// sentence that says so when they were scaled, else nothing.
    std::string fit_settings_to_document();
    void set_scene_field(const std::string& path);
    void set_import_field(const std::string& path);
    void set_export_field(const std::string& path);

    // ---- File dialogs (app_file_dialogs.cpp, panel_file_browser.cpp) ---------------------
    /// Open..., Save As..., Import... and Export...: the desktop's dialog program when there
    /// is one (and it is wanted), else the editor's own browser. One dialog at a time.
    void show_file_dialog(FileDialogKind kind);
    /// The dialog program to run, or nothing for the editor's browser: the setting, or
    /// SANDTIN_FILE_DIALOG, says which; "auto" is the program found on PATH, except in a
    /// scripted run, which always has the browser (a script drives it the same on any desktop).
    std::optional<DialogProgram> native_dialog_program();
    /// Where a dialog starts: the last folder a dialog picked in, else the folder of the
    /// field's path, else the working folder.
    std::filesystem::path dialog_start_folder(FileDialogKind kind) const;
    bool file_dialog_open() const {
        return browser_.is_open() || (native_dialog_ && native_dialog_->busy());
    }
    /// A file picked in either dialog goes where its field's button sends the field's path:
    /// Open and Import behind the unsaved-edits prompt, Save As behind the overwrite prompt.
    /// The path lands in the field, its folder in the settings (last_folder).
    void apply_picked_file(FileDialogKind kind, const std::filesystem::path& path);
    /// The desktop dialog's answer, taken on the UI thread; a dialog that failed gives way to
    /// the browser, and the status line says why.
    void take_native_dialog_result();
    /// The File panel's Open..., Save As..., Import... and Export... buttons.
    void file_dialog_buttons();
    /// The browser, while it is open (a modal window).
    void file_browser_window();
    /// The folder, the filters and the error; returns the file Enter in the filter picked.
    std::optional<std::filesystem::path> file_browser_header();
    /// The folder's entries; returns the file a double click picked.
    std::optional<std::filesystem::path> file_browser_entries(float height);
    void file_browser_footer(std::optional<std::filesystem::path>& picked);
    /// The script's pick_file op: the dialog's button, then the browser driven by real input.
    void queue_pick_file_op(const nlohmann::json& op);
    void queue_typing(const std::string& text);

    // ---- Solver (app_frame.cpp) ----------------------------------------------------------
    /// Whether the relaxation runs now: the Run/Pause switch, unless this document is still
    /// held (document.hpp: an opened scene waits for Run).
    bool erosion_runs() const { return settings_.erosion_running && !doc_.erosion_held(); }
    /// The Run/Pause button: Run also releases a held document.
    void toggle_erosion();
    /// Gives the document the solver the Erosion panel asks for (CPU or GPU). `switched`: the
    /// new solver looks at every vertex once and the status line says where it runs.
    void attach_solver(bool switched);
    /// Lets go of the current terrain in the order its users depend on each other (the solver,
    /// then the views), before the document is replaced or destroyed.
    void release_terrain();
    /// The Erosion panel's choice resolved on this device: Auto is the GPU on a hardware GPU
    /// and the CPU on a software device (gpu/device_selection.hpp).
    bool gpu_physics_wanted() const;
    /// "relaxation on the CPU (Auto: llvmpipe is a software device)": for the status line.
    std::string physics_placement_text() const;
    /// The Erosion panel's state line (erosion_status.hpp).
    std::string erosion_status() const;

    // ---- One frame (app_frame.cpp) -------------------------------------------------------
    bool frame(bool capture);
    void update_simulation();
    void update_haptics();
    void draw_terrain(const Mat4& view_projection);
    /// The current stamp tool's inner contour at the cursor, on the terrain (render frame).
    std::vector<std::array<float, 3>> footprint_outline();
    /// The current stamp tool as the next stamp will be (built again when the tool, Size or
    /// Extrude changed).
    const Tool& cursor_tool();

    // ---- Input (app_input.cpp) -----------------------------------------------------------
    std::optional<Vec3> pick(double x, double y) const;
    /// Picks a tool by key or panel: not in the middle of a stroke.
    void pick_tool(int index);
    /// What a shortcut's key does (shortcuts.hpp).
    void run_command(Command command);

    // ---- Panels (panel_*.cpp) ------------------------------------------------------------
    void draw_panels();
    /// Every control explains itself on hover; the tooltip shown is noted (widget map).
    void tip(const char* text);
    /// A control with a name: noted in the widget map, where scripted clicks and the xdotool
    /// test find it, then explained by `text` on hover.
    void ui(const std::string& name, const char* text);
    /// A button of a two-answer prompt, named "<prompt>/<label>" in the widget map.
    struct PromptButton {
        const char* prompt;
        const char* label;
        const char* tip;
    };
    /// The prompt's two buttons side by side: true for `yes`, false for `no`, nullopt while
    /// neither was clicked. An answer closes the popup.
    std::optional<bool> answer_buttons(const PromptButton& yes, const PromptButton& no);
    float status_window_height() const;
    void status_window(float height);
    void panel_file();
    void panel_tools();
    void tool_sliders();
    /// In place of the Size slider for a stamp it does not size: the stamp's own extent.
    void stamp_size_readout();
    void panel_materials();
    void panel_erosion();
    /// The Water panel (panel_water.cpp): flow, rain, evaporation, open sides, the depth
    /// overlay, Clear, and how much water there is.
    void panel_water();
    /// One frame of water (app_frame.cpp): the held Water tool, rain, the flow.
    void update_water();
    void panel_haptics();
    /// The Stats window's first lines: vertex and triangle counts, constrained edges and
    /// volume (their length sizes the window).
    std::array<std::string, 2> stats_terrain_lines() const;
    /// Every line of text the Stats window shows, made before the window so that its width
    /// can be that of the widest.
    struct StatsText {
        std::array<std::string, 2> terrain;
        std::array<std::string, 3> timing;  ///< stats_lines.hpp
        std::string normal_map;
    };
    StatsText stats_text() const;
    void panel_stats(const StatsText& text);
    void stats_window();
    /// The list of keys and gestures (F1; shortcuts.hpp).
    void help_window();
    /// What the recovery prompt says: which scene, and how old its autosave is.
    std::string recovery_prompt_text() const;
    void recovery_prompt();
    void discard_prompt();
    void overwrite_prompt();
    /// The running job's modal bar with Cancel (panel_progress.cpp).
    void job_window();
    /// The erosion's settle to rest: its bar with Stop, while it lasts.
    void settle_window();

    // ---- Scripted mode (app_script.cpp) --------------------------------------------------
    void run_script_op(const nlohmann::json& op);
    void run_setting_op(const nlohmann::json& op);
    void queue_pointer_op(const std::string& kind, const nlohmann::json& op);
    void queue_prompt_op(const std::string& kind, const nlohmann::json& op);
    void run_document_op(const std::string& kind, const nlohmann::json& op);
    /// Runs the next real-input step of a scripted op (each step is followed by a frame).
    void run_input_step();
    /// The centre of the control `name` as the last frame drew it (window pixels); nullopt
    /// while it is not (yet) on screen.
    std::optional<std::pair<double, double>> widget_centre(const std::string& name) const;
    /// Queues a click of `button` at a window position (pointer there, then down, then up,
    /// each in its own frame, as a hand does), with Ctrl held when `ctrl`.
    void queue_click(std::function<std::pair<double, double>()> where, int button, bool ctrl);
    /// A click on a control: waits for it to be on screen first.
    void queue_widget_click(const std::string& name, bool ctrl, const std::string& why_missing);
    void queue_key(int glfw_key, bool ctrl);
    /// The ops about long work: jobs, job, cancel_job, resume_job.
    void run_job_op(const std::string& kind, const nlohmann::json& op);
    void set_physics(const std::string& name);
    /// "face" or "edge" (EditorSettings::slope_rule); a change wakes every vertex, since sand
    /// at rest under one rule need not be under the other.
    void set_slope_rule(const std::string& name);
    void set_falloff(const std::string& name);

    // ---- State ---------------------------------------------------------------------------
    EditorOptions options_;
    std::filesystem::path settings_path_;
    EditorSettings settings_;
    EditorSettings saved_settings_;
    // The window before everything drawn in it, so that it goes last.
    std::unique_ptr<EditorWindow> window_;
    /// Real input for scripted runs; each step injects events and is followed by one frame.
    /// Goes before the window (it restores the X server's auto-repeat on its connection).
    std::unique_ptr<XInput> x_input_;
    std::unique_ptr<TerrainView> view_;
    Document doc_;
    Sculpting sculpting_;
    AutosaveWriter autosave_writer_;   ///< finishes a queued autosave when the editor closes
    bool autosave_in_script_ = false;  ///< a script's "autosave" op turns autosaving on
    bool autosaves() const { return !options_.scripted() || autosave_in_script_; }
    bool gpu_physics_failed_ = false;  ///< the GPU solver could not start: the CPU's for now
    std::size_t erosion_active_ = 0;   ///< vertices the last relaxation step left active

    OrbitCamera camera_;
    StageTimes times_;
    std::string status_;
    std::vector<std::string> messages_;  ///< every status message, for a scripted run's stats
    LayoutProbe layout_;                 ///< how far the panels' controls reach past their edges
    WidgetMap widgets_;                  ///< where the named controls were drawn
    std::string published_widgets_;      ///< the map last written to --widget-map
    /// Opens (true) or closes every panel header in the next frame (the script's "panels" op).
    std::optional<bool> open_panels_;
    bool help_open_ = false;       ///< the Help window (F1)
    double idle_cpu_share_ = 0.0;  ///< --idle-seconds: CPU seconds per second while idle
    std::uint64_t events_seen_ = 0;
    Clock::time_point last_frame_at_{};
    int redraw_frames_ = 2;  ///< frames still to draw after the last event (ImGui settles)
    std::uint64_t last_upload_bytes_ = 0;

    // Pointer.
    bool left_down_ = false, right_down_ = false, middle_down_ = false;
    double mouse_x_ = 0.0, mouse_y_ = 0.0;
    std::optional<Vec3> cursor_;
    Clock::time_point hold_clock_{};                ///< when a held button last counted its time
    Clock::time_point water_clock_ = Clock::now();  ///< when the water last counted its time
    /// The water on the terrain as last measured: after each frame the water ran, and by
    /// the Water panel a few times a second (an undo may change it).
    WaterSummary water_summary_;
    Clock::time_point water_summary_at_{};

    // Prompts.
    std::optional<std::filesystem::path> recovery_for_;
    std::function<void()> pending_replacement_;  ///< waits for the discard prompt
    std::string pending_replacement_label_;
    /// A save that would replace another file waits for the overwrite prompt.
    struct PendingOverwrite {
        std::filesystem::path path;
        std::function<void()> then;
    };
    std::optional<PendingOverwrite> pending_overwrite_;
    bool quit_confirmed_ = false;
    bool prompt_open() const {
        return recovery_for_.has_value() || pending_replacement_ != nullptr ||
               pending_overwrite_.has_value() || browser_.is_open();
    }

    // Long work (app_jobs.cpp).
    std::unique_ptr<BackgroundJob> job_;
    std::string job_kind_;            ///< "open", "import" or "export"
    std::function<void()> job_done_;  ///< takes the job's result on the UI thread
    bool job_popup_open_ = false;     ///< the modal is closed in the frame after the job ends
    nlohmann::json job_record_;       ///< what the running job's bar showed
    std::vector<nlohmann::json> jobs_done_;  ///< the records of the jobs that ended
    std::vector<double> install_ms_;         ///< each install_document's time on the UI thread
    /// Keys typed while a job ran, for when it has ended (App::key); at most kKeysAfterJob.
    static constexpr std::size_t kKeysAfterJob = 16;
    std::vector<std::pair<int, bool>> keys_after_job_;
    bool script_job_must_succeed_ = false;  ///< a script's save: its failure fails the run
    bool startup_open_ = false;             ///< the running job opens the command line's scene
    nlohmann::json startup_job_record_;     ///< its record, once it ended
    bool script_waits_for_jobs_ = true;     ///< a script's next op waits for the job to end
    std::optional<double> job_pause_at_;    ///< test hook (background_job.hpp)
    SettleProgress settle_;
    Clock::time_point last_settle_at_{};
    nlohmann::json settle_record_ = nlohmann::json::object();

    // Haptics panel.
    std::unique_ptr<HapticsSession> haptics_;
    int haptic_device_ = 0;  ///< HapticDeviceKind
    int haptic_rate_hz_ = 1000;
    int haptic_udp_port_ = 0;
    std::string haptics_error_;
    std::optional<Tool> haptic_tool_;
    int haptic_tool_index_ = -1;
    double haptic_tool_radius_ = 0.0;
    std::deque<float> haptic_forces_;

    // The cursor's tool (outline and Size readout).
    std::optional<Tool> cursor_tool_;
    int cursor_tool_index_ = -1;
    double cursor_tool_radius_ = 0.0;
    bool cursor_tool_extrude_ = false;

    // Scripted mode.
    std::vector<nlohmann::json> script_;
    std::size_t script_pos_ = 0;
    int script_wait_ = 0;
    /// A step returns false to be tried again next frame (a control not on screen yet).
    std::deque<std::function<bool()>> input_steps_;

    // File dialogs.
    FileBrowser browser_;
    std::unique_ptr<NativeFileDialog> native_dialog_;
    FileDialogRequest native_request_;  ///< what the desktop's dialog was asked

    // The File panel's fields.
    char path_buf_[512] = "scene.sandtin";
    char import_buf_[512] = "";
    char export_buf_[512] = "terrain.glb";
};

}  // namespace sandtin::editor
