// Set-up, the loops, and what a scripted run writes at its end.

#include "app.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>

#include "default_sandbox.hpp"
#include "formats/png_image.hpp"
#include "recent_files.hpp"
#include "tool_palette.hpp"
#include "util/atomic_file.hpp"
#include "util/json_document.hpp"
#include "util/process_cpu_time.hpp"

namespace sandtin::editor {

// ---- Set-up -------------------------------------------------------------------------------

App::~App() {
    // The force loop fades the force out before the window goes; nothing the GPU may still
    // read is destroyed before it is idle; the document's GPU solver and the terrain's views
    // go before the device. A job still running is cancelled and waited for first (it
    // touches nothing of the editor's but the GPU, and its result would never be taken; a
    // result not taken yet holds GPU buffers), and a desktop file dialog still open is closed:
    // its thread wakes GLFW's loop, which must still be there.
    job_.reset();
    job_done_ = nullptr;
    native_dialog_.reset();
    haptics_.reset();
    if (window_) window_->wait_idle();
    release_terrain();
    doc_ = Document();
    view_.reset();
    x_input_.reset();
    window_.reset();
}

void App::release_terrain() {
    // The GPU solver relaxes on the view's mirror, and the view reads the TIN's journal: the
    // solver goes first, then what the view built on the TIN, then (the caller) the TIN.
    if (!doc_.has_terrain()) return;
    doc_.drop_solver();
    if (view_) view_->release();
}

Document App::initial_document() {
    if (options_.scene.empty()) return Document::sandbox();
    // A missing scene is a mistake on the command line: said before any window opens. The
    // scene itself is read on a worker behind the progress bar (start_opening_initial_scene).
    if (!std::filesystem::exists(options_.scene)) {
        throw std::runtime_error("scene " + options_.scene.string() + " does not exist");
    }
    return Document::placeholder();
}

void App::start_opening_initial_scene() {
    if (options_.scene.empty()) return;
    // A script's leading "jobs" ops set how the jobs it starts run (pause_at, wait): they apply
    // to this one too, so a test can see the command line's scene held under its bar.
    while (script_pos_ < script_.size() && script_[script_pos_].value("op", "") == "jobs")
        run_script_op(script_[script_pos_++]);
    open_reporting(options_.scene);
    startup_open_ = true;
}

void App::initial_scene_failed(const std::string& problem) {
    const std::string text = "cannot open " + options_.scene.string() + ": " + problem;
    // A script cannot go on without its scene: it fails, as with any bad input. The artist
    // gets the sandbox and the reason on the status line.
    if (options_.scripted()) throw std::runtime_error(text);
    install_document(Document::sandbox(), text + "; a new sandbox instead");
}

void App::offer_recovery_of(const std::filesystem::path& scene) {
    // An autosave newer than the scene: the prompt asks, however the scene was opened (the
    // command line, Open, the recent list or a drop).
    if (const auto info = find_autosave(scene); info && info->offer_recovery())
        recovery_for_ = scene;
}

void App::report(const std::string& message) {
    status_ = message;
    // The session's messages, for the stats a scripted run writes (the line shows the last).
    if (messages_.size() < 1000) messages_.push_back(message);
    if (std::getenv("SANDTIN_EDITOR_TRACE") != nullptr)
        std::fprintf(stderr, "sandtin-editor: %s\n", message.c_str());
}

std::uint64_t App::gpu_work() {
    return window_->swapchain().submissions() + view_->gpu_work() +
           doc_.solver().device_dispatches();
}

void App::save_settings_reporting() {
    // Tried once per change: a settings file that cannot be written (a read-only home) must
    // not stop the editor, nor make every frame try again.
    saved_settings_ = settings_;
    try {
        save_settings(settings_path_, settings_);
    } catch (const std::exception& e) {
        report(std::string("cannot save the editor settings: ") + e.what());
    }
}

LoopState App::loop_state() const {
    LoopState state;
    window_->framebuffer_size(state.framebuffer_width, state.framebuffer_height);
    // A new terrain's normal map is baked a band a frame: frames go on until it is whole.
    state.redraw_pending = redraw_frames_ > 0 || view_->baking_normal_map();
    state.dragging = left_down_;
    state.prompt_open = prompt_open();
    state.job_running = busy();
    // The sand waits while a job runs (update_simulation): its frames are the job's.
    state.eroding = !busy() && erosion_runs() && sculpting_.wants_to_erode(doc_);
    state.water_moving = !busy() && !doc_.water().idle(water_settings(settings_));
    state.haptics_connected = haptics_ != nullptr;
    return state;
}

bool App::wait_for_events(const LoopState& state, double at_most_seconds) {
    const std::uint64_t seen = events_seen_;
    double wait = event_wait_seconds(state);
    if (at_most_seconds >= 0.0)
        wait = wait < 0.0 ? at_most_seconds : std::min(wait, at_most_seconds);
    if (wait == 0.0) {
        glfwPollEvents();
    } else if (wait > 0.0) {
        glfwWaitEventsTimeout(wait);
    } else {
        glfwWaitEvents();
    }
    // A blocking wait returns only for an event (perhaps one no callback counts).
    const bool event_arrived = wait < 0.0 || events_seen_ != seen;
    return draw_after_wait(state, event_arrived,
                           std::chrono::duration<double>(Clock::now() - last_frame_at_).count());
}

void App::interactive_loop() {
    while (!close_confirmed()) {
        // Idle or minimised: block until an event arrives; no frame, no submission (with a
        // haptic device, a readout frame now and then: frame_policy.hpp).
        if (!wait_for_events(loop_state(), kWaitForEvent)) continue;
        int w = 0, h = 0;
        window_->framebuffer_size(w, h);
        if (!can_draw(w, h)) continue;  // minimised since the wait began
        frame(false);
        publish_widget_map();
        if (redraw_frames_ > 0) --redraw_frames_;
        if (!(settings_ == saved_settings_)) save_settings_reporting();
    }
}

void App::publish_widget_map() {
    if (options_.widget_map.empty()) return;
    const std::string text = widgets_.to_json().dump() + "\n";
    if (text == published_widgets_) return;  // an idle editor writes nothing
    try {
        write_file_atomically(options_.widget_map,
                              std::span<const std::uint8_t>(
                                  reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
        published_widgets_ = text;
    } catch (const std::exception& e) {
        report(std::string("cannot write the widget map: ") + e.what());
        options_.widget_map.clear();
    }
}

void App::load_settings_reporting() {
    settings_path_ = options_.settings.empty() ? default_settings_path() : options_.settings;
    std::string problem;
    settings_ = load_settings(settings_path_, &problem);
    settings_.tool = std::clamp(settings_.tool, 0, kToolCount - 1);
    saved_settings_ = settings_;
    if (!problem.empty()) {
        // On the status line, where the artist looks, not only on a terminal nobody reads.
        std::fprintf(stderr, "sandtin-editor: %s\n", problem.c_str());
        report(problem);
    }
}

int App::run() {
    load_settings_reporting();
    if (!options_.script.empty()) {
        const nlohmann::json j = read_json_document(options_.script, "editor script");
        if (!j.contains("ops") || !j["ops"].is_array())
            throw std::runtime_error("script " + options_.script.string() +
                                     " has no \"ops\" array");
        for (const auto& op : j["ops"])
            script_.push_back(op);
    }
    Document first = initial_document();
    window_ = std::make_unique<EditorWindow>(options_.width, options_.height, options_.validation,
                                             settings_.vsync, this, install_callbacks);
    view_ = std::make_unique<TerrainView>(window_->context(), window_->renderer());
    if (options_.scripted()) x_input_ = std::make_unique<XInput>(window_->glfw());
    const std::string settings_problem = status_;
    status_.clear();
    install_document(std::move(first), "");
    // The status line starts with what the settings file had to say, what the scene asked of
    // the tools (scaled to its size), and where the relaxation runs.
    std::string start = settings_problem;
    for (const std::string& part : {status_, physics_placement_text()}) {
        if (!part.empty()) start += (start.empty() ? "" : "; ") + part;
    }
    report(start);
    std::fprintf(stderr, "sandtin-editor: %s\n", window_->context().describe().c_str());
    start_opening_initial_scene();

    int exit_code = 0;
    std::vector<std::string> output_failures;
    std::uint64_t idle_submissions = 0, idle_gpu_work = 0;
    // Whatever goes wrong in a session, scripted or interactive, its edits are not lost with the
    // editor: they go to the autosave first (offered for recovery next time), then the error is
    // reported. A script's edits go there only once it asked for autosaving ("autosave" op).
    try {
        if (options_.scripted()) {
            scripted_loop();
            output_failures = write_outputs();
            if (options_.idle_seconds > 0.0) idle_measurement(idle_submissions, idle_gpu_work);
        } else {
            interactive_loop();
            sculpting_.close_level(doc_);
            keep_unsaved_edits();  // closing with unsaved edits: they wait in the autosave
        }
    } catch (const std::exception&) {
        try {
            keep_unsaved_edits();
        } catch (const std::exception& autosave) {
            std::fprintf(stderr, "sandtin-editor: emergency autosave failed: %s\n",
                         autosave.what());
        }
        throw;
    }

    const std::uint64_t validation = window_->context().validation_message_count();
    if (!options_.stats.empty()) write_stats(idle_submissions, idle_gpu_work);
    for (const std::string& failure : output_failures)
        std::fprintf(stderr, "sandtin-editor: %s\n", failure.c_str());
    if (!output_failures.empty()) exit_code = 1;
    if (validation > 0) {
        for (const std::string& m : window_->context().validation_messages())
            std::fprintf(stderr, "validation: %s\n", m.c_str());
        exit_code = 3;
    }
    if (!options_.scripted() && !(settings_ == saved_settings_)) save_settings_reporting();
    return exit_code;
}

void App::scripted_loop() {
    const bool trace = std::getenv("SANDTIN_EDITOR_TRACE") != nullptr;
    int frames_after_script = 0;
    // Every op runs between frames; an op that is real input (a click, a key, a drag) is a
    // sequence of steps, each of which sends its X events, lets GLFW deliver them, and is
    // followed by one frame, as when a hand moves the mouse.
    while (!close_confirmed()) {
        glfwPollEvents();
        if (!input_steps_.empty()) {
            run_input_step();
        } else if (script_wait_ > 0) {
            --script_wait_;
        } else if (busy() && script_waits_for_jobs_) {
            // The next op waits for the import, open or export the last one started.
        } else if (script_pos_ < script_.size()) {
            run_script_op(script_[script_pos_++]);
            if (!input_steps_.empty()) run_input_step();
            if (trace)
                std::fprintf(stderr, "sandtin-editor: op %zu %s -> %zu vertices\n", script_pos_,
                             script_[script_pos_ - 1].dump().c_str(), doc_.tin().vertex_count());
        } else {
            sculpting_.close_level(doc_);
            ++frames_after_script;
        }
        // The last frame shows the view finished: its normal map baked whole.
        const bool last = script_pos_ >= script_.size() && script_wait_ == 0 &&
                          input_steps_.empty() && !view_->baking_normal_map() &&
                          frames_after_script >= std::max(1, options_.frames);
        frame(last && !options_.screenshot.empty());
        if (last) break;
    }
}

void App::idle_measurement(std::uint64_t& submissions, std::uint64_t& work) {
    // Idle: nothing changed, nothing drawn; count what reaches the queue meanwhile, and the
    // CPU time the whole process (every thread, the Vulkan driver's too) spends.
    const double cpu_before = process_cpu_seconds();
    const auto wall_before = Clock::now();
    const std::uint64_t before = window_->swapchain().submissions();
    const std::uint64_t work_before = gpu_work();
    const auto until = Clock::now() + std::chrono::duration<double>(options_.idle_seconds);
    settings_.erosion_running = false;
    redraw_frames_ = 0;
    // The interactive loop's waits and decisions, bounded by the idle time.
    while (Clock::now() < until) {
        const double left = std::chrono::duration<double>(until - Clock::now()).count();
        if (!wait_for_events(loop_state(), std::max(left, 1e-3))) continue;
        frame(false);
        if (redraw_frames_ > 0) --redraw_frames_;
    }
    submissions = window_->swapchain().submissions() - before;
    work = gpu_work() - work_before;
    idle_cpu_share_ = (process_cpu_seconds() - cpu_before) /
                      std::chrono::duration<double>(Clock::now() - wall_before).count();
}

void App::write_stats(std::uint64_t idle_submissions, std::uint64_t idle_gpu_work) {
    nlohmann::json s;
    s["device"] = window_->context().device_name();
    s["frames"] = times_.frame.size();
    s["frame_ms_median"] = StageTimes::median(times_.frame);
    // The UI thread's share of each document installed (the start's, New, Open, Import,
    // Recover), in ms: what a worker could not take (issue 42).
    s["install_ms"] = install_ms_;
    s["tool_ms_median"] = StageTimes::median(times_.tool);
    // A scripted drag applies its whole stroke between two frames: the largest frame's
    // tool time is that stroke's cost.
    s["tool_ms_max"] =
        times_.tool.empty()
            ? 0.0
            : static_cast<double>(*std::max_element(times_.tool.begin(), times_.tool.end()));
    s["physics_ms_median"] = StageTimes::median(times_.physics);
    s["physics"] = to_string(doc_.solver().device());
    s["erosion_status"] = erosion_status();
    s["erosion_running"] = erosion_runs();
    s["mesh_ms_median"] = StageTimes::median(times_.mesh);
    s["upload_ms_median"] = StageTimes::median(times_.upload);
    s["bake_ms_median"] = StageTimes::median(times_.bake);
    s["normal_map_bakes"] = view_->normal_map_bakes();
    s["normal_map_texels_baked"] = view_->normal_map() ? view_->normal_map()->texels_baked() : 0;
    s["render_ms_median"] = StageTimes::median(times_.render);
    s["fps"] =
        StageTimes::median(times_.frame) > 0 ? 1000.0 / StageTimes::median(times_.frame) : 0.0;
    s["vertices"] = doc_.tin().vertex_count();
    s["triangles"] = doc_.tin().triangle_count();
    s["undo_levels"] = doc_.undo_log().levels();
    {
        const WaterSummary w = doc_.water().measure();
        s["water"] = {{"m3", w.volume},
                      {"wet_vertices", w.wet_vertices},
                      {"max_depth_m", w.max_depth},
                      {"resting", doc_.water().resting()},
                      {"sand_carried_m3", doc_.water().suspended()},
                      // What the last frame drew the water's surface on (0: no water pass).
                      {"surface_triangles", window_->renderer().water_triangles_drawn()}};
    }
    s["submissions"] = window_->swapchain().submissions();
    s["bytes_uploaded"] = window_->renderer().bytes_uploaded();
    s["mesh_updates"] = view_->mesh_updates();
    s["mesh_rebuilds"] = view_->mesh_rebuilds();
    s["mesh_vertices_recomputed"] = view_->vertices_recomputed();
    s["idle_submissions"] = idle_submissions;
    s["idle_gpu_work"] = idle_gpu_work;
    s["idle_cpu_share"] = idle_cpu_share_;  // CPU seconds per second while idle (all threads)
    s["validation_messages"] = window_->context().validation_message_count();
    s["layout_overflow_px"] = layout_.overflow_px();
    s["layout_hidden_px"] = layout_.hidden_px();
    s["status"] = status_;
    s["messages"] = messages_;
    s["scene_path"] = doc_.path().string();
    s["scene_field"] = std::string(path_buf_);
    s["dirty"] = doc_.dirty();
    s["tooltip"] = widgets_.last_tooltip();
    s["widgets"] = widgets_.to_json();
    s["help_open"] = help_open_;
    s["jobs"] = jobs_done_;
    s["startup_job"] = startup_job_record_;  // the scene named on the command line, if any
    s["job_running"] = busy();
    s["settle"] = settle_record_;
    s["recent_files"] = settings_.recent_files;
    s["last_folder"] = settings_.last_folder;
    s["import_field"] = std::string(import_buf_);
    s["export_field"] = std::string(export_buf_);
    s["file_browser"] = {{"open", browser_.is_open()},
                         {"folder", browser_.folder().string()},
                         {"error", browser_.error()},
                         {"message", browser_.message()}};
    s["native_dialog_busy"] = native_dialog_ != nullptr && native_dialog_->busy();
    if (recovery_for_) s["recovery_prompt"] = recovery_prompt_text();
    s["settings"] = {{"tool_radius", settings_.tool_radius},
                     {"tool_depth", settings_.tool_depth},
                     {"stroke_spacing_ratio", settings_.stroke_spacing_ratio},
                     {"pour_volume", settings_.pour_volume},
                     {"brush_strength", settings_.brush_strength},
                     {"brush_blend", settings_.brush_blend},
                     {"erosion_steps", settings_.erosion_steps},
                     {"relocation_radius", settings_.relocation_radius},
                     {"settle_margin", settings_.settle_margin},
                     {"slope_rule", settings_.slope_rule},
                     {"settle_fit_bends", settings_.settle_fit_bends},
                     {"simplify_tolerance", settings_.simplify_tolerance},
                     {"contrast", settings_.contrast},
                     {"tool_angle", settings_.tool_angle}};
    if (haptics_) {
        const HapticsLive l = haptics_->live();
        s["haptics"] = {{"device", l.device},
                        {"rate_hz", l.rate_hz},
                        {"ticks", l.ticks},
                        {"force_n", l.force_n},
                        {"contact", l.contact},
                        {"stale", l.stale},
                        {"device_lost", l.device_lost},
                        {"backup_thread", l.backup_thread}};
    }
    if (cursor_) s["cursor"] = {cursor_->x, cursor_->y, cursor_->z};
    double px = 0, py = 0;
    int w = 0, h = 0;
    window_->window_size(w, h);
    if (cursor_) {
        const Vec2 c = doc_.tin().domain().centre();
        if (camera_.project({cursor_->x - c.x, cursor_->y - c.y, cursor_->z}, w, h, px, py))
            s["cursor_pixel"] = {px, py};
    }
    std::ofstream(options_.stats) << s.dump(2) << "\n";
}

std::vector<std::string> App::write_outputs() {
    std::vector<std::string> failures;
    if (!options_.save_after.empty()) {
        try {
            save_now(options_.save_after);
        } catch (const std::exception& e) {
            failures.push_back("cannot save the scene: " + std::string(e.what()));
            keep_unsaved_edits();  // as when a session fails: to the autosave, if it has one
        }
    }
    if (!options_.screenshot.empty()) {
        try {
            write_png(options_.screenshot, window_->swapchain().screenshot());
        } catch (const std::exception& e) {
            failures.push_back("cannot write the screenshot: " + std::string(e.what()));
        }
    }
    return failures;
}

int run_editor(const EditorOptions& options) {
    App app(options);
    return app.run();
}

}  // namespace sandtin::editor
