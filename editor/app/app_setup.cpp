// Set-up, document operations and the main loop of the editor.

#include "app.hpp"
#include "io/session_name.hpp"
#include "util/json_document.hpp"

namespace sandtin::editor {

namespace {

App* app_of(GLFWwindow* w) {
    return static_cast<App*>(glfwGetWindowUserPointer(w));
}

void on_button(GLFWwindow* w, int b, int action, int mods) {
    app_of(w)->note_event();
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    (void)mods;
    const bool down = action == GLFW_PRESS;
    if (down && ImGui::GetIO().WantCaptureMouse) return;
    app_of(w)->mouse_button(b, down, x, y);
}
void on_cursor(GLFWwindow* w, double x, double y) {
    app_of(w)->note_event();
    app_of(w)->mouse_move(x, y);
}
void on_wheel(GLFWwindow* w, double, double dy) {
    app_of(w)->note_event();
    if (ImGui::GetIO().WantCaptureMouse) return;
    app_of(w)->scroll(dy);
}
void on_key(GLFWwindow* w, int key, int, int action, int mods) {
    app_of(w)->note_event();
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    app_of(w)->key(key, (mods & GLFW_MOD_CONTROL) != 0);
}

// Events that only ImGui or the window itself act on still ask for a frame (typing into a
// field, focus, exposure, resizing): the loop's timed waits tell them from a plain timeout.
void on_char(GLFWwindow* w, unsigned int) {
    app_of(w)->note_event();
}
void on_focus(GLFWwindow* w, int) {
    app_of(w)->note_event();
}
void on_cursor_enter(GLFWwindow* w, int) {
    app_of(w)->note_event();
}
void on_refresh(GLFWwindow* w) {
    app_of(w)->note_event();
}
void on_framebuffer_size(GLFWwindow* w, int, int) {
    app_of(w)->note_event();
}
void on_iconify(GLFWwindow* w, int) {
    app_of(w)->note_event();
}

}  // namespace

// ---- Set-up -------------------------------------------------------------------------------

void App::load_initial_scene() {
    if (options_.scene.empty()) {
        doc_.adopt(default_sandbox(), 1, {});
        doc_.tin->take_changes();
        return;
    }
    if (!std::filesystem::exists(options_.scene)) {
        throw std::runtime_error("scene " + options_.scene.string() + " does not exist");
    }
    const Session s = load_session(options_.scene);
    doc_.adopt(session_terrain(s, options_.scene), s.next_generation, options_.scene,
               materials_or_presets(s.metadata_json), s.metadata_json);
    // An autosave newer than the scene: the prompt asks (a script answers with "recovery").
    if (const auto info = find_autosave(options_.scene); info && info->offer_recovery())
        recovery_for_ = options_.scene;
}

void App::init_window_and_gpu() {
    if (glfwInit() != GLFW_TRUE) {
        throw std::runtime_error(
            "cannot open a window: no display (set DISPLAY, or run under "
            "xvfb-run -s '-screen 0 1280x720x24')");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(options_.width, options_.height, "sandtin", nullptr, nullptr);
    if (window_ == nullptr) throw std::runtime_error("glfwCreateWindow failed");
    glfwSetWindowUserPointer(window_, this);
    glfwSetMouseButtonCallback(window_, on_button);
    glfwSetCursorPosCallback(window_, on_cursor);
    glfwSetScrollCallback(window_, on_wheel);
    glfwSetKeyCallback(window_, on_key);
    // Installed before ImGui's backend, which chains to the ones it replaces.
    glfwSetCharCallback(window_, on_char);
    glfwSetWindowFocusCallback(window_, on_focus);
    glfwSetCursorEnterCallback(window_, on_cursor_enter);
    glfwSetWindowRefreshCallback(window_, on_refresh);
    glfwSetFramebufferSizeCallback(window_, on_framebuffer_size);
    glfwSetWindowIconifyCallback(window_, on_iconify);

    gpu::ContextOptions o;
    std::uint32_t n = 0;
    const char** ext = glfwGetRequiredInstanceExtensions(&n);
    if (ext == nullptr) throw std::runtime_error("GLFW finds no Vulkan surface support");
    o.instance_extensions.assign(ext, ext + n);
    GLFWwindow* win = window_;
    o.make_surface = [win](VkInstance instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        if (glfwCreateWindowSurface(instance, win, nullptr, &surface) != VK_SUCCESS)
            return VkSurfaceKHR{VK_NULL_HANDLE};
        return surface;
    };
    o.validation = options_.validation;
    context_ = std::make_unique<gpu::VulkanContext>(o);
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    swapchain_ = std::make_unique<Swapchain>(
        *context_, VkExtent2D{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)},
        settings_.vsync);
    renderer_ = std::make_unique<render::TerrainRenderer>(*context_, swapchain_->render_pass());
    mesh_ = std::make_unique<render::TerrainMesh>(doc_.materials);
}

void App::init_imgui() {
    const VkDevice device = context_->device();
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 16;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    VkDescriptorPool handle = VK_NULL_HANDLE;
    gpu::check(vkCreateDescriptorPool(device, &pool, nullptr, &handle), "vkCreateDescriptorPool");
    imgui_pool_ = gpu::UniqueDescriptorPool(device, handle);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // panel layout is fixed; settings live in our file
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window_, true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context_->instance();
    info.PhysicalDevice = context_->physical_device();
    info.Device = device;
    info.QueueFamily = context_->queue_family();
    info.Queue = context_->queue();
    info.DescriptorPool = handle;
    info.MinImageCount = 2;
    info.ImageCount = std::max(2u, swapchain_->image_count());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    ImGui_ImplVulkan_Init(&info, swapchain_->render_pass());
    context_->submit_and_wait([](VkCommandBuffer cb) { ImGui_ImplVulkan_CreateFontsTexture(cb); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    imgui_ready_ = true;
}

void App::shutdown() {
    haptics_.reset();  // the loop fades the force out before the window goes
    if (swapchain_) swapchain_->wait_idle();
    if (context_) vkDeviceWaitIdle(context_->device());
    if (imgui_ready_) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        imgui_ready_ = false;
    }
    // The normal map and the GPU mirrors hold device objects: they go before the device too.
    normal_map_.reset();
    own_mirror_.reset();
    if (doc_.physics && doc_.physics->backend() == ErosionBackend::Gpu) doc_.physics.reset();
    renderer_.reset();
    imgui_pool_.reset();
    swapchain_.reset();
    context_.reset();
    if (window_ != nullptr) glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
}

// ---- Document operations ------------------------------------------------------------------

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

void App::fit_settings_to_document() {
    const double size = terrain_size(doc_.tin->domain());
    const double k = fit_settings_to_terrain(settings_, size);
    doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance;
    if (k != 1.0) {
        cursor_tool_.reset();  // built at the old size
        haptic_tool_.reset();
        char text[160];
        std::snprintf(text, sizeof(text),
                      "tool size, depth, brush, pour, r_S and simplification scaled "
                      "x%.3g for this %.4g m terrain",
                      k, size);
        report(text);
    }
}

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

void App::open(const std::filesystem::path& p) {
    end_action();
    keep_unsaved_edits();
    const Session s = load_session(p);
    doc_.adopt(session_terrain(s, p), s.next_generation, p, materials_or_presets(s.metadata_json),
               s.metadata_json);
    document_replaced();
    frame_terrain();
    report("opened " + p.string());
}

Tool App::build_tool() const {
    // The assets are made for the 1 m sandbox: on another terrain they keep their proportion
    // to it, and round tools take the Size slider's radius.
    ToolSpec spec =
        scaled_tool_spec(load_tool_asset(kTools[settings_.tool].asset), settings_.scene_size);
    if (sized_by_slider(spec)) spec.radius = settings_.tool_radius;
    spec.extrude = settings_.extrude;
    return Tool::build(spec);
}

void App::end_action() {
    if (sampler_) {
        for (const StrokeSample& s : sampler_->finish()) {
            StrokeSettings ss;
            ss.depth = settings_.tool_depth;
            ss.follow_path = settings_.follow_path;
            ss.angle = settings_.tool_angle * 3.14159265358979 / 180.0;
            const ToolPlacement at =
                placement_for(*doc_.tin, *active_tool_, s, ss, &doc_.context->hint);
            const StampReport r = stamp(*doc_.tin, *active_tool_, at, *doc_.context, s.direction);
            if (const std::optional<std::string> w = lost_extrusion_warning(r)) report(*w);
        }
        sampler_.reset();
    }
    end_pour();
    if (!pending_label_.empty()) {
        if (doc_.history->record(pending_label_)) {
            mark_edited();
            undo_log_.push_terrain(pending_label_);
        }
        pending_label_.clear();
    }
    if (erosion_pending_) {
        if (doc_.history->record("erosion")) {
            mark_edited();
            undo_log_.push_terrain("erosion");
        }
        erosion_pending_ = false;
    }
    resettling_ = false;
}

void App::apply_materials(const MaterialTable& table) {
    doc_.materials = table;
    // Both solvers re-read the angles of repose and look at every vertex again.
    doc_.physics->set_materials(doc_.materials);
    mesh_->set_materials(doc_.materials);
    mesh_stale_ = true;  // colours and slope ratios of every vertex
    physics_kick_ = true;
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
        if (std::getenv("SANDTIN_EDITOR_TRACE") != nullptr) {
            for (Vec2 p : step.report.unrestored) {
                LocateHint h;
                const Location loc = doc_.tin->locate(p, &h);
                for (VertexId c : loc.corners) {
                    if (doc_.tin->position(c) == p)
                        std::fprintf(stderr, "unrestored %.6f %.6f boundary %d constraint %d\n",
                                     p.x, p.y, doc_.tin->is_boundary(c),
                                     doc_.tin->is_on_constraint(c));
                }
            }
        }
    }
    if (step.label == "erosion" && settings_.erosion_running) {
        // Running on, the physics would slide the restored sand straight back.
        settings_.erosion_running = false;
        message += "; erosion paused";
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

// ---- Main loop ------------------------------------------------------------------------------

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
    glfwGetFramebufferSize(window_, &state.framebuffer_width, &state.framebuffer_height);
    state.redraw_pending = redraw_frames_ > 0;
    state.dragging = left_down_;
    state.prompt_open = recovery_for_.has_value() || pending_replacement_ != nullptr;
    state.eroding = settings_.erosion_running && (physics_kick_ || !doc_.physics->at_rest());
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
        glfwGetFramebufferSize(window_, &w, &h);
        if (!can_draw(w, h)) continue;  // minimised since the wait began
        frame(false);
        if (redraw_frames_ > 0) --redraw_frames_;
        if (!(settings_ == saved_settings_)) save_settings_reporting();
    }
}

int App::run() {
    settings_path_ = options_.settings.empty() ? default_settings_path() : options_.settings;
    std::string problem;
    settings_ = load_settings(settings_path_, &problem);
    if (!problem.empty()) std::fprintf(stderr, "sandtin-editor: %s\n", problem.c_str());
    settings_.tool = std::clamp(settings_.tool, 0, kToolCount - 1);
    saved_settings_ = settings_;
    if (!options_.script.empty()) {
        const nlohmann::json j = read_json_document(options_.script, "editor script");
        if (!j.contains("ops") || !j["ops"].is_array())
            throw std::runtime_error("script " + options_.script.string() +
                                     " has no \"ops\" array");
        for (const auto& op : j["ops"])
            script_.push_back(op);
    }
    load_initial_scene();
    if (!options_.scene.empty())
        std::snprintf(path_buf_, sizeof(path_buf_), "%s", options_.scene.c_str());
    init_window_and_gpu();
    init_imgui();
    document_replaced();  // the journal's fan-out, and the GPU solver if the settings ask
    std::fprintf(stderr, "sandtin-editor: %s\n", context_->describe().c_str());
    frame_terrain();

    int exit_code = 0;
    std::vector<std::string> output_failures;
    std::uint64_t idle_submissions = 0, idle_gpu_work = 0;
    int frames_after_script = 0;
    // Whatever goes wrong in a session, scripted or interactive, its edits are not lost with the
    // editor: they go to the autosave first (offered for recovery next time), then the error is
    // reported. A script's edits go there only once it asked for autosaving ("autosave" op).
    try {
        if (options_.scripted()) {
            const bool trace = std::getenv("SANDTIN_EDITOR_TRACE") != nullptr;
            // Scripted: every op runs between frames through the real input handlers.
            while (!close_confirmed()) {
                glfwPollEvents();
                if (script_wait_ > 0) {
                    --script_wait_;
                } else if (script_pos_ < script_.size()) {
                    run_script_op(script_[script_pos_++]);
                    if (trace)
                        std::fprintf(stderr, "sandtin-editor: op %zu %s -> %zu vertices\n",
                                     script_pos_, script_[script_pos_ - 1].dump().c_str(),
                                     doc_.tin->vertex_count());
                } else {
                    end_action();
                    ++frames_after_script;
                }
                const bool last = script_pos_ >= script_.size() && script_wait_ == 0 &&
                                  frames_after_script >= std::max(1, options_.frames);
                frame(last && !options_.screenshot.empty());
                if (last) break;
            }
            output_failures = write_outputs();
            if (options_.idle_seconds > 0.0) {
                // Idle: nothing changed, nothing drawn; count what reaches the queue meanwhile.
                const std::uint64_t before = swapchain_->submissions();
                const std::uint64_t work_before = gpu_work();
                const auto until =
                    Clock::now() + std::chrono::duration<double>(options_.idle_seconds);
                settings_.erosion_running = false;
                redraw_frames_ = 0;
                // The interactive loop's waits and decisions, bounded by the idle time.
                while (Clock::now() < until) {
                    const double left = std::chrono::duration<double>(until - Clock::now()).count();
                    if (!wait_for_events(loop_state(), std::max(left, 1e-3))) continue;
                    frame(false);
                    if (redraw_frames_ > 0) --redraw_frames_;
                }
                idle_submissions = swapchain_->submissions() - before;
                idle_gpu_work = gpu_work() - work_before;
            }
        } else {
            interactive_loop();
            end_action();
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

    const std::uint64_t validation = context_->validation_message_count();
    if (!options_.stats.empty()) {
        nlohmann::json s;
        s["device"] = context_->device_name();
        s["frames"] = times_.frame.size();
        s["frame_ms_median"] = StageTimes::median(times_.frame);
        s["tool_ms_median"] = StageTimes::median(times_.tool);
        // A scripted drag applies its whole stroke between two frames: the largest frame's
        // tool time is that stroke's cost.
        s["tool_ms_max"] =
            times_.tool.empty()
                ? 0.0
                : static_cast<double>(*std::max_element(times_.tool.begin(), times_.tool.end()));
        s["physics_ms_median"] = StageTimes::median(times_.physics);
        s["physics"] = doc_.physics->backend() == ErosionBackend::Gpu ? "gpu" : "cpu";
        s["erosion_status"] = erosion_status();
        s["mesh_ms_median"] = StageTimes::median(times_.mesh);
        s["upload_ms_median"] = StageTimes::median(times_.upload);
        s["bake_ms_median"] = StageTimes::median(times_.bake);
        s["normal_map_bakes"] = normal_map_bakes_;
        s["normal_map_texels_baked"] = normal_map_ ? normal_map_->texels_baked() : 0;
        s["render_ms_median"] = StageTimes::median(times_.render);
        s["fps"] =
            StageTimes::median(times_.frame) > 0 ? 1000.0 / StageTimes::median(times_.frame) : 0.0;
        s["vertices"] = doc_.tin->vertex_count();
        s["triangles"] = doc_.tin->triangle_count();
        s["undo_levels"] = doc_.history->undo_levels();
        s["submissions"] = swapchain_->submissions();
        s["bytes_uploaded"] = renderer_->bytes_uploaded();
        s["mesh_updates"] = mesh_updates_;
        s["mesh_rebuilds"] = mesh_rebuilds_;
        s["mesh_vertices_recomputed"] = mesh_recomputed_;
        s["idle_submissions"] = idle_submissions;
        s["idle_gpu_work"] = idle_gpu_work;
        s["validation_messages"] = validation;
        s["layout_overflow_px"] = layout_.overflow_px();
        s["layout_hidden_px"] = layout_.hidden_px();
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
        glfwGetWindowSize(window_, &w, &h);
        if (cursor_) {
            const Vec2 c = doc_.tin->domain().centre();
            if (camera_.project({cursor_->x - c.x, cursor_->y - c.y, cursor_->z}, w, h, px, py))
                s["cursor_pixel"] = {px, py};
        }
        std::ofstream(options_.stats) << s.dump(2) << "\n";
    }
    for (const std::string& failure : output_failures)
        std::fprintf(stderr, "sandtin-editor: %s\n", failure.c_str());
    if (!output_failures.empty()) exit_code = 1;
    if (validation > 0) {
        for (const std::string& m : context_->validation_messages())
            std::fprintf(stderr, "validation: %s\n", m.c_str());
        exit_code = 3;
    }
    if (!options_.scripted() && !(settings_ == saved_settings_)) save_settings_reporting();
    shutdown();
    return exit_code;
}

std::vector<std::string> App::write_outputs() {
    std::vector<std::string> failures;
    if (!options_.save_after.empty()) {
        try {
            save(options_.save_after);
        } catch (const std::exception& e) {
            failures.push_back("cannot save the scene: " + std::string(e.what()));
            keep_unsaved_edits();  // as when a session fails: to the autosave, if it has one
        }
    }
    if (!options_.screenshot.empty()) {
        try {
            write_png(options_.screenshot, swapchain_->screenshot());
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
