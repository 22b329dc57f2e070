#pragma once
// The editor application: one window, one document, panels, input, scripted mode. Its member
// functions are spread over app_*.cpp by job (set-up and main loop, input, script, per-frame
// update, panels).

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "camera.hpp"
#include "change_fanout.hpp"
#include "editor_settings.hpp"
#include "erosion_status.hpp"
#include "formats/png_image.hpp"
#include "frame_policy.hpp"
#include "gpu/gpu_error.hpp"
#include "gpu/render/normal_map.hpp"
#include "gpu/render/terrain_mesh.hpp"
#include "gpu/render/terrain_renderer.hpp"
#include "gpu/vulkan_context.hpp"
#include "history/history.hpp"
#include "io/autosave.hpp"
#include "io/autosave_writer.hpp"
#include "io/export_terrain.hpp"
#include "io/heightmap_import.hpp"
#include "io/import_grid.hpp"
#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "layout_probe.hpp"
#include "panel_layout.hpp"
#include "physics/sand_physics.hpp"
#include "picking.hpp"
#include "pour_flow.hpp"
#include "swapchain.hpp"
#include "terrain_scale.hpp"
#include "tools/brushes.hpp"
#include "tools/falloff.hpp"
#include "tools/sand.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

#include "document.hpp"
#include "editor_app.hpp"
#include "haptics_session.hpp"
#include "stage_times.hpp"
#include "tool_palette.hpp"
#include "undo_log.hpp"
#include "widget_map.hpp"
#include "x_input.hpp"

namespace sandtin::editor {

using Clock = std::chrono::steady_clock;

/// Milliseconds of relaxation per frame at most (the rest waits for the next frame).
inline constexpr double kErosionBudgetMs = 25.0;

/// Seconds a frame of a scripted run counts for (a held pour): 60 frames a second, so a
/// script pours the same on any machine, however fast it draws.
inline constexpr double kScriptFrameSeconds = 1.0 / 60.0;

/// The undo level of sand the erosion moved with no gesture of the artist's before it.
inline constexpr const char* kErosionLevel = "erosion";

inline double ms_since(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

class App {
  public:
    explicit App(const EditorOptions& o) : options_(o) {}
    /// Also on errors: ImGui's and the swapchain's Vulkan objects go before the device.
    ~App() { shutdown(); }
    App(const App&) = delete;
    App& operator=(const App&) = delete;
    int run();

    void load_settings_reporting();
    /// The scene named on the command line, or a new sandbox.
    Document initial_document();
    void init_window_and_gpu();
    void init_imgui();
    void shutdown();
    bool frame(bool capture);
    void update_simulation();
    /// Gives the document the solver the Erosion panel asks for (CPU or GPU). `switched`: the
    /// new solver looks at every vertex once (it does not know what the old one had left).
    void attach_physics(bool switched);
    /// The Erosion panel's choice resolved on this device: Auto is the GPU on a hardware GPU
    /// and the CPU on a software device (gpu/device_selection.hpp).
    bool gpu_physics_wanted() const;
    /// "relaxation on the CPU (Auto: llvmpipe is a software device)": for the status line.
    std::string physics_placement_text() const;
    bool gpu_physics_failed_ = false;  ///< the GPU solver could not start: the CPU's for now
    void update_mesh();
    /// Syncs the GPU mirror and re-bakes the normal map where the terrain changed (the caller
    /// waited for the previous frame).
    void update_normal_map();
    /// Every piece of GPU work so far: frames submitted, normal-map bakes, mirror upload
    /// batches and relaxation dispatches. An idle editor adds nothing to it.
    std::uint64_t gpu_work() {
        gpu::TinMirror* m = doc_.physics->mirror();
        if (m == nullptr) m = own_mirror_.get();
        return swapchain_->submissions() + normal_map_bakes_ +
               (m != nullptr ? m->staging().batches_submitted() : 0) +
               doc_.physics->gpu_dispatches();
    }

    // ---- Panels (app_panels.cpp) ----
    void draw_panels();
    /// Every control explains itself on hover; the tooltip shown is noted (widget map).
    void tip(const char* text);
    /// A control with a name: noted in the widget map, where scripted clicks and the xdotool
    /// test find it, then explained by `text` on hover.
    void ui(const std::string& name, const char* text);
    /// Pixels the status window takes at the bottom of the window with its margin (0 when
    /// there is no status).
    float status_window_height() const;
    /// The status line in its own window, pinned below the panel (`height` as above).
    void status_window(float height);
    void panel_tools();
    void panel_materials();
    void panel_erosion();
    /// The Erosion panel's state line (erosion_status.hpp).
    std::string erosion_status() const {
        if (doc_.erosion_held && settings_.erosion_running)
            return "paused for the opened scene: Run lets it settle";
        return erosion_status_text(erosion_runs(), doc_.physics->at_rest(), erosion_active_);
    }
    /// Whether the relaxation runs now: the Run/Pause switch, unless this document is still
    /// held (document.hpp: an opened scene waits for Run).
    bool erosion_runs() const { return settings_.erosion_running && !doc_.erosion_held; }
    /// The Run/Pause button: Run also releases a held document.
    void toggle_erosion();
    void panel_haptics();
    /// The Stats window's first lines: vertex and triangle counts, constrained edges and
    /// volume (their length sizes the window).
    std::array<std::string, 2> stats_terrain_lines() const;
    void panel_stats(const std::array<std::string, 2>& terrain_lines);
    void panel_file();
    void recovery_prompt();
    void discard_prompt();
    void overwrite_prompt();

    // ---- Document operations (app_document.cpp) ----
    /// The one way a document replaces another (New, Open, Import, Recover, and the scene at
    /// start-up): everything that depends on the terrain is torn down and built again for the
    /// new one (mesh, renderer buffers, GPU mirror, normal map, physics, undo, journal
    /// readers), and the mesh and normal map are built before anything draws, so no frame
    /// ever draws one terrain with another's GPU objects, wherever this is called from.
    void install_document(Document next, const std::string& message);
    /// The recovery prompt's answer (its buttons).
    void answer_recovery(bool recover);
    /// Replaces the document (New, Open, Import) through `action`; when that would drop the
    /// unsaved edits of an untitled scene (no file, so no autosave to keep them), the user is
    /// asked first. A scene with a file keeps its edits in the autosave (keep_unsaved_edits).
    void replace_document(const std::string& what, std::function<void()> action);
    /// The discard prompt's answers. Save writes the scene where Save and Ctrl+S write an
    /// untitled one (the File panel's Scene field: the editor has no file dialog), then goes on.
    enum class DiscardChoice { Save, Discard, Cancel };
    /// The discard prompt's answer (its buttons).
    void answer_discard(DiscardChoice choice);
    /// The window was asked to close and may: an untitled scene with unsaved edits asks
    /// first (the discard prompt), and the window stays open meanwhile.
    bool close_confirmed();
    void new_document();
    /// Opens the scene named in the Scene field; a failure is reported.
    void open_reporting();
    void open(const std::filesystem::path& p);
    /// Imports the heightmap named in the Heightmap field as an untitled scene, and fills the
    /// Scene field with a name of its own; a failure is reported.
    void import_document();
    void save(const std::filesystem::path& p);
    /// Save, Save As, Ctrl+S and the prompts' Save: writes the scene to `p`, then runs `then`.
    /// A file at `p` that is not this scene's own is replaced only after the overwrite prompt
    /// says so. A failure is reported on the status line and `then` does not run.
    void request_save(const std::filesystem::path& p, std::function<void()> then = {});
    /// Save and Ctrl+S: a failure is reported on the status line. True when saved.
    bool save_reporting(const std::filesystem::path& p);
    /// The terrain to a mesh or height map, as `sandtin export` writes it (format from the
    /// extension), with the materials as the viewport shows them. Throws on failure.
    void export_to(const std::filesystem::path& p);
    /// Where Save and Ctrl+S write: the scene's file, or the Scene field for an untitled one.
    std::filesystem::path save_path() const {
        return doc_.path.empty() ? std::filesystem::path(path_buf_) : doc_.path;
    }
    void frame_terrain();
    /// The length settings follow the new document's terrain size (terrain_scale.hpp), and the
    /// document's sculpting context takes the panel's simplification tolerance. Returns the
    /// sentence that says so when they were scaled, else nothing.
    std::string fit_settings_to_document();
    /// Waits until the GPU no longer uses anything: before objects a submitted frame or
    /// solver step may still read (the normal map, the mirrors) are destroyed.
    void wait_gpu_idle() const {
        if (context_) vkDeviceWaitIdle(context_->device());
    }
    /// The document changed: it needs saving, and an autosave once the interval has passed.
    void mark_edited() {
        doc_.dirty = true;
        autosave_schedule_.edited(Clock::now());
    }
    /// Autosaves a document with unsaved edits a minute after the first of them (on the
    /// writer's thread: the frame only takes the snapshot), and shows a failed write.
    void autosave_if_due();
    /// Before the document is replaced (New, Open, Import): unsaved edits of a scene with a
    /// file go to its autosave, which is offered for recovery when the scene is opened again.
    void keep_unsaved_edits();
    void undo();
    void redo();
    /// A new material table everywhere it is used (physics, mesh colours); not an undo level.
    void apply_materials(const MaterialTable& table);
    /// The Materials panel's edit of material `index` (released control): an undo level.
    void edit_material(int index, const Material& m);

    // ---- Strokes and undo levels (app_input.cpp) ----
    void mouse_button(int button, bool down, double x, double y);
    /// Every GLFW callback calls this first: the loop's timed waits tell events from timeouts,
    /// and the haptic snapshot is no longer held (the event may edit the terrain).
    void note_event() {
        ++events_seen_;
        if (haptics_) haptics_->release();
        // ImGui settles over the frames after an event: a click that closes a prompt leaves
        // it open in the frame that handles the click, and until another frame is drawn ImGui
        // still says it wants the keyboard, so the next shortcut would be swallowed.
        redraw_frames_ = std::max(redraw_frames_, 3);
    }
    void mouse_move(double x, double y);
    void scroll(double dy);
    void key(int key, bool ctrl);
    /// Runs an input handler; an error in it (a tool that refuses its parameters, a file
    /// that cannot be read) is shown on the status line and the gesture under way is ended,
    /// never thrown through GLFW (C code) or out of the editor.
    template <class F>
    void guarded(const char* what, F&& handler) {
        try {
            handler();
        } catch (const std::exception& e) {
            abandon_gesture();
            report(std::string(what) + ": " + e.what());
        }
    }
    std::optional<Vec3> pick(double x, double y) const;
    void tool_at(Vec3 point);
    /// The Pour or Remove tool at `xy` (press or move): the dabs the pour flow places there.
    void pour_at(Vec2 xy);
    /// One dab of the Pour or Remove tool, of the Pour slider's volume.
    void pour_dab(Vec2 at);
    /// A pour held down keeps pouring with time (pour_flow.hpp); called once per frame.
    void pour_while_held();
    /// Ends the Pour or Remove gesture; one that moved less sand than asked says so.
    void end_pour();
    /// Metres: the pour's disc is half the Size slider's radius.
    double pour_radius() const { return 0.5 * settings_.tool_radius; }
    /// The gesture under way (a stroke's last stamps, a pour) ends; its undo level stays open
    /// while the sand it disturbed settles (settle_erosion closes it), so that one stroke and
    /// its settling undo together.
    void end_gesture();
    /// The gesture, and the undo level it and the erosion since opened, end now: before
    /// anything else changes the document (a new stroke, undo, save, a switch of solver).
    void end_action();
    /// An error stopped the gesture: what it did so far stays and becomes its undo level.
    void abandon_gesture();
    /// The erosion came to rest: simplify what it moved, let the sand settle that, and close
    /// the open undo level.
    void settle_erosion();

    // ---- Scripted mode (app_script.cpp) ----
    void run_script_op(const nlohmann::json& op);
    /// Runs the next real-input step of a scripted op (each step is followed by a frame).
    void run_input_step();
    /// The centre of the control `name` as the last frame drew it (window pixels); nullopt
    /// while it is not (yet) on screen.
    std::optional<std::pair<double, double>> widget_centre(const std::string& name) const;
    /// Queues a click of `button` at a window position (pointer there, then down, then up,
    /// each in its own frame, as a hand does), with Ctrl held when `ctrl`.
    void queue_click(std::function<std::pair<double, double>()> where, int button, bool ctrl);
    void queue_key(int glfw_key, bool ctrl);
    void set_physics(const std::string& name);
    void set_falloff(const std::string& name);
    /// The script's "scene_path": typed into the File panel's Scene field.
    void set_scene_field(const std::string& path);
    /// The script's "import_path": typed into the File panel's Heightmap field.
    void set_import_field(const std::string& path);
    /// A scripted run's outputs, data first: the scene (--save-after), then the screenshot.
    /// Each is tried whatever became of the other (a bad screenshot path once lost the
    /// scene); the failures are returned, for the run to report and exit 1 with.
    std::vector<std::string> write_outputs();
    /// Writes the widget map to --widget-map when it changed (the xdotool test reads it).
    void publish_widget_map();

    /// The interactive main loop: until the window closes.
    void interactive_loop();
    /// The scripted loop: every op, then the frames asked for.
    void scripted_loop();
    void idle_measurement(std::uint64_t& submissions, std::uint64_t& gpu_work);
    void write_stats(std::uint64_t idle_submissions, std::uint64_t idle_gpu_work);
    LoopState loop_state() const;
    /// Waits as frame_policy.hpp decides for `state`, for at most `at_most_seconds` when that
    /// is not kWaitForEvent, and says whether to draw a frame now.
    bool wait_for_events(const LoopState& state, double at_most_seconds);
    std::uint64_t events_seen_ = 0;
    Clock::time_point last_frame_at_{};
    /// Writes the settings file after a change; a failure is reported, not thrown.
    void save_settings_reporting();
    void report(const std::string& message) {
        status_ = message;
        // The session's messages, for the stats a scripted run writes (the line shows the last).
        if (messages_.size() < 1000) messages_.push_back(message);
        if (std::getenv("SANDTIN_EDITOR_TRACE") != nullptr)
            std::fprintf(stderr, "sandtin-editor: %s\n", message.c_str());
    }
    Tool build_tool() const;

    EditorOptions options_;
    std::filesystem::path settings_path_;
    EditorSettings settings_;
    EditorSettings saved_settings_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<gpu::VulkanContext> context_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<render::TerrainRenderer> renderer_;
    std::unique_ptr<render::TerrainMesh> mesh_;
    /// The one consumer of the TIN's change journal; the mesh and the GPU mirror take from it.
    std::unique_ptr<ChangeFanout> fanout_;
    /// The TIN on the GPU for the normal-map bake while the CPU erodes (the GPU physics brings
    /// its own mirror, which the bake then shares).
    std::unique_ptr<gpu::TinMirror> own_mirror_;
    std::unique_ptr<render::TerrainNormalMap> normal_map_;
    std::uint64_t normal_map_bakes_ = 0;
    std::uint64_t normal_map_texels_ = 0;   ///< texels of the last re-bake
    std::vector<VertexId> active_ids_;      ///< vertices flagged active now
    std::vector<VertexId> active_flipped_;  ///< flags that changed since the last mesh update
    std::uint64_t last_upload_bytes_ = 0;
    std::uint64_t mesh_updates_ = 0, mesh_rebuilds_ = 0, mesh_recomputed_ = 0;
    gpu::UniqueDescriptorPool imgui_pool_;
    bool imgui_ready_ = false;
    Document doc_;
    UndoLog undo_log_;  ///< terrain levels (doc_.history) and material edits, in order
    OrbitCamera camera_;
    StageTimes times_;
    std::string status_;
    std::vector<std::string> messages_;
    LayoutProbe layout_;             ///< how far the panels' controls reach past their edges
    WidgetMap widgets_;              ///< where the named controls were drawn
    std::string published_widgets_;  ///< the map last written to --widget-map
    /// Opens (true) or closes every panel header in the next frame (the script's "panels" op).
    std::optional<bool> open_panels_;

    // Interaction state.
    bool left_down_ = false, right_down_ = false, middle_down_ = false;
    double mouse_x_ = 0.0, mouse_y_ = 0.0;
    std::optional<Vec3> cursor_;
    std::optional<StrokeSampler> sampler_;
    std::optional<Tool> active_tool_;
    std::optional<Vec2> last_dab_;
    std::optional<PourFlow> pour_flow_;           ///< the Pour or Remove gesture under way
    bool pour_removes_ = false;                   ///< that gesture is a Remove
    Clock::time_point pour_clock_{};              ///< when the held pour last counted its time
    double pour_asked_ = 0.0, pour_moved_ = 0.0;  ///< m³ over the gesture (moved < 0: removed)
    double flatten_level_ = 0.0;  ///< metres: the Flatten brush's level for this stroke
    /// The undo level being made: the gesture's label ("stroke (Ball)") from its first edit
    /// until the sand it disturbed rests; "erosion" when the erosion alone moved sand.
    std::string open_level_;
    /// The erosion's simplification ran; the sand settles what it steepened (settle_erosion).
    bool resettling_ = false;
    bool physics_kick_ = true;
    /// Vertices the last relaxation step left active. Read right after a step, when both
    /// solvers have taken every pending activation (the GPU solver's count between steps adds
    /// its pending list, which may repeat vertices).
    std::size_t erosion_active_ = 0;
    std::vector<std::uint8_t> active_;
    double tool_ms_ = 0.0;
    bool mesh_stale_ = true;
    int redraw_frames_ = 2;  ///< frames still to draw after the last event (ImGui settles)
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
    AutosaveSchedule autosave_schedule_{std::chrono::seconds(60)};
    AutosaveWriter autosave_writer_;   ///< finishes a queued autosave when the editor closes
    bool autosave_in_script_ = false;  ///< a script's "autosave" op turns autosaving on
    bool autosaves() const { return !options_.scripted() || autosave_in_script_; }

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
    void update_haptics();
    void update_contrast_range();
    /// The current stamp tool's inner contour at the cursor, on the terrain (render frame).
    std::vector<std::array<float, 3>> footprint_outline();
    /// The current stamp tool as the next stamp will be (built again when the tool, Size or
    /// Extrude changed).
    const Tool& cursor_tool();
    /// In place of the Size slider for a stamp it does not size: the stamp's own extent.
    void stamp_size_readout();
    std::optional<Tool> cursor_tool_;
    int cursor_tool_index_ = -1;
    double cursor_tool_radius_ = 0.0;
    bool cursor_tool_extrude_ = false;
    double last_heading_ = 0.0;  ///< radians: direction of the stroke's last sample
    double contrast_low_ = 0.0, contrast_high_ = 0.1;  ///< m, heights the curve stretches
    Clock::time_point contrast_at_{};
    bool contrast_stale_ = true;

    // Scripted mode.
    std::vector<nlohmann::json> script_;
    std::size_t script_pos_ = 0;
    int script_wait_ = 0;
    /// Real input for scripted runs; each step injects events and is followed by one frame.
    std::unique_ptr<XInput> x_input_;
    /// A step returns false to be tried again next frame (a control not on screen yet).
    std::deque<std::function<bool()>> input_steps_;
    char path_buf_[512] = "scene.sandtin";
    char import_buf_[512] = "";
    char export_buf_[512] = "terrain.glb";
};

}  // namespace sandtin::editor
