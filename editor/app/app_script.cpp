// Scripted mode: JSON ops. Mouse and keyboard ops are real input: X events (x_input.hpp) that
// reach the editor through GLFW's queue and ImGui exactly as a hand's do, one step per frame.

#include "app.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "tool_palette.hpp"
#include "tools/falloff.hpp"

namespace sandtin::editor {

// ---- Script ---------------------------------------------------------------------------------
//
// {"ops": [ {"op": "tool", "name": "Ball"}  (its key, as an artist picks it)
//         | {"op": "set", "<setting>": value, ...}
//         | {"op": "drag", "button": "left"|"right"|"middle", "path": [[fx, fy], ...], "steps": n}
//         | {"op": "click", "at": [fx, fy]} | {"op": "click", "widget": "Save", "ctrl": false}
//         | {"op": "move", "at": [fx, fy]} | {"op": "hover", "widget": "Size"}
//         | {"op": "press", "at": [fx, fy]} | {"op": "release"}  (the left button held down
//            across frames: a "wait" between them holds it still, each frame counting 1/60 s)
//         | {"op": "key", "key": "z"|"enter"|"escape"|"backspace"|..., "ctrl": true}
//         | {"op": "type", "text": "..."}  (characters into whatever has the keyboard)
//         | {"op": "scroll", "steps": s} | {"op": "wait", "frames": n}
//         | {"op": "camera", "yaw": rad, "pitch": rad, "zoom": steps}
//         | {"op": "haptics", "connect": true|false, "rate": hz}
//         | {"op": "recovery", "choice": "recover"|"discard"}  (clicks the autosave prompt's
//            button)
//         | {"op": "discard", "choice": "save"|"discard"|"cancel"}  (clicks the button of the
//            prompt before New, Open, Import or closing drops an untitled scene's unsaved edits)
//         | {"op": "overwrite", "choice": "replace"|"cancel"}  (the prompt before a save
//            replaces another file)
//         | {"op": "close"}  (the window manager's close request)
//         | {"op": "resize", "size": [w, h]}  (the window, in screen pixels)
//         | {"op": "panels", "open": true|false}  (every panel header, from the next frame)
//         | {"op": "erode", "frames": n}  (Run, as its button: a held scene is let go too)
//         | {"op": "settle", "frames": n}  (waits until the sand rests and its undo level is
//            closed: at most n frames, 600 by default, else the script fails)
//         | {"op": "save", "path": "..."} | {"op": "export", "path": "..."}
//         | {"op": "autosave"}  (unsaved edits to the autosave now, as on closing)
//         | {"op": "save_settings"}  (writes the settings file, as a panel change does)
//         | {"op": "drop", "paths": ["...", ...]}  (files dropped on the window: what GLFW's
//            drop callback hands over, to the same handler)
//         | {"op": "pick_file", "dialog": "open"|"save_as"|"import"|"export",
//            "path": "/folder/name", "cancel": false, "replace": false}  (clicks the File
//            panel's Open..., Save As..., Import... or Export... button, then drives the
//            editor's file browser with real input: types the folder into its folder field,
//            types the name into its type-to-filter box and clicks the file in the list (Open,
//            Import) or types it into its name field (Save As, Export), then clicks its pick
//            button, or Cancel when "cancel"; "replace" answers the browser's overwrite question.
//            A scripted run shows the browser unless SANDTIN_FILE_DIALOG (or the file_dialog
//            setting) is "native": then the desktop's dialog program picks, "path" is not used,
//            and the op waits (up to 30 s) for the program's answer)
//         | {"op": "jobs", "wait": true|false, "pause_at": f}  (whether the ops after one that
//            starts an import, open, recovery or export wait for it to end, as by default; with
//            pause_at, a job holds at its first report at or past fraction f until
//            "resume_job" or Cancel: a test sees the bar mid-way on any machine. The script's
//            leading "jobs" ops apply to the opening of the scene named on the command line
//            too, which the ops after them wait for unless they said "wait": false)
//         | {"op": "job", "until": "paused"|"done", "frames": n}  (waits for the running
//            job to hold at its pause point, or to end: at most n frames, 600 by default)
//         | {"op": "cancel_job"}  (clicks the job's Cancel, or the settle bar's Stop)
//         | {"op": "resume_job"}
//         | {"op": "stage_times", "ms": t}  (from now on every stage of every frame counts as
//            taking t ms, as on a slow machine: the Stats window's fit, whatever the machine)
//         | {"op": "material", "index": i, "repose_dry": deg, "repose_moist": deg,
//            "colour": [r, g, b]}  (the Materials panel's edit: one undo level) ] }
// Widget names are the panels' (app_panels.cpp: the names given to ui()); prompts' buttons are
// "recovery/Recover", "unsaved/Discard", "overwrite/Replace" and so on. A click on a widget
// waits (up to 10 frames) until it is on screen and has stopped moving.
// "set" knows radius, depth, material, erosion, wireframe, slope, pour_volume, brush_strength
// (Raise and Lower, metres per dab), brush_blend (Smooth and Flatten, 0..1 per dab), falloff
// ("constant" | "linear" | "smooth" | "gaussian"), steps, relocation_radius,
// simplify_tolerance (metres, as the Erosion panel's slider), physics ("auto" | "cpu" | "gpu", the
// Erosion panel's switch), slope_rule ("face" | "edge", its Repose on switch), scene_path and
// import_path (typed into the File panel's Scene and Heightmap fields), export_path (the Export
// field); numbers are clamped to their sliders' ranges, as typed values are. Positions are
// fractions of the window (0..1): scripts work at any --size.

namespace {

/// The GLFW key a script names: one letter or digit, or a key's name.
int glfw_key_named(const std::string& name) {
    if (name.size() == 1) {
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
        if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
        if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
        if (c == '-') return GLFW_KEY_MINUS;
        if (c == '.') return GLFW_KEY_PERIOD;
    }
    static const std::pair<const char*, int> kNamed[] = {
        {"enter", GLFW_KEY_ENTER}, {"escape", GLFW_KEY_ESCAPE}, {"backspace", GLFW_KEY_BACKSPACE},
        {"tab", GLFW_KEY_TAB},     {"delete", GLFW_KEY_DELETE}, {"home", GLFW_KEY_HOME},
        {"end", GLFW_KEY_END},     {"left", GLFW_KEY_LEFT},     {"right", GLFW_KEY_RIGHT},
        {"up", GLFW_KEY_UP},       {"down", GLFW_KEY_DOWN},     {"space", GLFW_KEY_SPACE},
        {"f1", GLFW_KEY_F1}};
    for (const auto& [key_name, key] : kNamed) {
        if (name == key_name) return key;
    }
    throw std::runtime_error("script: no key named '" + name + "'");
}

/// Frames a click on a widget waits for it to appear and settle. Everything the editor shows
/// after an input is drawn in the next frame or two (a popup sizes itself in its first, hidden
/// frame): counted in frames, not seconds, so a slow machine waits as long.
constexpr int kWidgetWaitFrames = 10;

}  // namespace

void App::set_physics(const std::string& name) {
    if (name != "auto" && name != "cpu" && name != "gpu")
        throw std::runtime_error("script: physics must be auto, cpu or gpu, not '" + name + "'");
    if (name == settings_.physics) return;
    sculpting_.close_level(doc_);
    settings_.physics = name;
    attach_solver(true);
}

void App::set_slope_rule(const std::string& name) {
    if (name != "face" && name != "edge")
        throw std::runtime_error("script: slope_rule must be face or edge, not '" + name + "'");
    if (name == settings_.slope_rule) return;
    settings_.slope_rule = name;
    doc_.solver().activate_all();
    sculpting_.kick();
}

void App::set_falloff(const std::string& name) {
    if (!falloff_named(name)) {
        throw std::runtime_error(
            "script: falloff must be constant, linear, smooth or gaussian, not '" + name + "'");
    }
    settings_.brush_falloff = name;
}

std::optional<std::pair<double, double>> App::widget_centre(const std::string& name) const {
    const std::optional<WidgetRect> r = widgets_.find(name);
    if (!r || !widgets_.settled(name)) return std::nullopt;
    return std::pair<double, double>{r->centre_x(), r->centre_y()};
}

void App::run_input_step() {
    if (input_steps_.front()()) input_steps_.pop_front();
    // The events reach GLFW's queue, then its callbacks and state (which ImGui reads at the
    // start of the frame that follows).
    x_input_->sync();
    glfwPollEvents();
}

void App::queue_click(std::function<std::pair<double, double>()> where, int button, bool ctrl) {
    auto at = std::make_shared<std::pair<double, double>>();
    // The pointer goes there first, in a frame of its own: ImGui decides what is under the
    // pointer (a panel, or the terrain) from where it was in the last frame, as with a hand.
    input_steps_.push_back([this, where, at, ctrl] {
        *at = where();
        if (ctrl) x_input_->key(GLFW_KEY_LEFT_CONTROL, true);
        x_input_->move_to(at->first, at->second);
        return true;
    });
    input_steps_.push_back([this, button] {
        x_input_->button(button, true);
        return true;
    });
    input_steps_.push_back([this, button, ctrl] {
        x_input_->button(button, false);
        if (ctrl) x_input_->key(GLFW_KEY_LEFT_CONTROL, false);
        return true;
    });
}

void App::queue_key(int glfw_key, bool ctrl) {
    // Down and up in frames of their own: ImGui reads a key's state once per frame.
    input_steps_.push_back([this, glfw_key, ctrl] {
        if (ctrl) x_input_->key(GLFW_KEY_LEFT_CONTROL, true);
        x_input_->key(glfw_key, true);
        return true;
    });
    input_steps_.push_back([this, glfw_key, ctrl] {
        x_input_->key(glfw_key, false);
        if (ctrl) x_input_->key(GLFW_KEY_LEFT_CONTROL, false);
        return true;
    });
}

void App::queue_typing(const std::string& text) {
    input_steps_.push_back([this, text] {
        for (char c : text)
            x_input_->type(c);
        return true;
    });
}

void App::queue_pick_file_op(const nlohmann::json& op) {
    const std::string dialog = op.at("dialog").get<std::string>();
    const std::optional<FileDialogKind> kind = file_dialog_kind_named(dialog);
    if (!kind) {
        throw std::runtime_error(
            "script: pick_file dialog must be open, save_as, import or export, not '" + dialog +
            "'");
    }
    static constexpr const char* kButtons[] = {"Open...", "Save As...", "Import...", "Export..."};
    queue_widget_click(kButtons[static_cast<int>(*kind)], false, "the File panel is closed");
    if (native_dialog_program()) {
        // The desktop's program picks: wait for its answer, as a hand would.
        auto started = std::make_shared<std::optional<Clock::time_point>>();
        input_steps_.push_back([this, started] {
            if (!*started) *started = Clock::now();
            // Answered: its file applied, or (a failure) the browser open in its place.
            if (!native_dialog_ || !native_dialog_->busy()) return true;
            if (Clock::now() - **started > std::chrono::seconds(30))
                throw std::runtime_error("script: the file dialog did not answer within 30 s");
            return false;
        });
        return;
    }
    const std::filesystem::path path = op.at("path").get<std::string>();
    const std::string name = path.filename().string();
    if (name.empty() || !path.has_parent_path())
        throw std::runtime_error("script: pick_file wants a folder and a file name, not '" +
                                 path.string() + "'");
    // To the folder: its field, everything in it selected, the folder typed, Enter.
    queue_widget_click("browser/Folder", false, "the file browser did not open");
    queue_key(GLFW_KEY_A, true);
    queue_typing(path.parent_path().string());
    queue_key(GLFW_KEY_ENTER, false);
    if (file_dialog_request(*kind, {}).saving) {
        queue_widget_click("browser/Name", false, "the file browser has no name field");
        queue_key(GLFW_KEY_A, true);
        queue_typing(name);
    } else {
        // The file among the folder's entries: the list narrowed to it, then clicked.
        queue_widget_click("browser/Filter", false, "the file browser has no filter box");
        queue_typing(name);
        queue_widget_click("browser/entry/" + name, false,
                           "no " + name + " listed in " + path.parent_path().string());
    }
    queue_widget_click(op.value("cancel", false) ? "browser/Cancel" : "browser/OK", false,
                       "the file browser closed early");
    if (op.value("replace", false))
        queue_widget_click("browser/Replace", false, "the browser did not ask to replace");
}

void App::queue_widget_click(const std::string& name, bool ctrl, const std::string& why_missing) {
    // Waits, frame after frame, for the control to be on screen and to stop moving.
    auto waited = std::make_shared<int>(0);
    auto at = std::make_shared<std::pair<double, double>>(-1.0, -1.0);
    input_steps_.push_back([this, name, why_missing, waited, at] {
        if (const auto c = widget_centre(name)) {
            *at = *c;
            return true;
        }
        if (++*waited > kWidgetWaitFrames)
            throw std::runtime_error("script: no control '" + name + "' on screen after " +
                                     std::to_string(kWidgetWaitFrames) + " frames" +
                                     (why_missing.empty() ? "" : ": " + why_missing));
        return false;
    });
    queue_click([at] { return *at; }, GLFW_MOUSE_BUTTON_LEFT, ctrl);
}

void App::run_script_op(const nlohmann::json& op) {
    const std::string kind = op.at("op").get<std::string>();
    if (kind == "set")
        run_setting_op(op);
    else if (kind == "tool" || kind == "click" || kind == "drag" || kind == "press" ||
             kind == "move" || kind == "hover" || kind == "release" || kind == "key" ||
             kind == "type" || kind == "scroll" || kind == "close")
        queue_pointer_op(kind, op);
    else if (kind == "recovery" || kind == "discard" || kind == "overwrite")
        queue_prompt_op(kind, op);
    else if (kind == "pick_file")
        queue_pick_file_op(op);
    else
        run_document_op(kind, op);
}

void App::run_setting_op(const nlohmann::json& op) {
    const double size = settings_.scene_size;
    for (const auto& [k2, v] : op.items()) {
        if (k2 == "op")
            continue;
        else if (k2 == "radius")
            settings_.tool_radius = kToolRadiusRange.clamp(v.get<double>(), size);
        else if (k2 == "depth")
            settings_.tool_depth = kToolDepthRange.clamp(v.get<double>(), size);
        else if (k2 == "material")
            settings_.material =
                std::clamp(v.get<int>(), 0, static_cast<int>(doc_.materials().size()) - 1);
        else if (k2 == "erosion")
            settings_.erosion_running = v.get<bool>();
        else if (k2 == "wireframe")
            settings_.overlay_wireframe = v.get<bool>();
        else if (k2 == "slope")
            settings_.overlay_slope = v.get<bool>();
        else if (k2 == "water_overlay")
            settings_.overlay_water = v.get<bool>();
        else if (k2 == "speed_overlay")
            settings_.overlay_water_speed = v.get<bool>();
        else if (k2 == "sediment_overlay")
            settings_.overlay_sediment = v.get<bool>();
        else if (k2 == "water_erode")
            settings_.water_erode = v.get<bool>();
        else if (k2 == "water_detail")
            settings_.water_detail = kWaterDetailRange.clamp(v.get<double>(), size);
        else if (k2 == "water_flowing")
            settings_.water_flowing = v.get<bool>();
        else if (k2 == "rain")
            settings_.water_rain = kWaterRainRange.clamp(v.get<double>(), size);
        else if (k2 == "evaporation")
            settings_.water_evaporation = kWaterEvaporationRange.clamp(v.get<double>(), size);
        else if (k2 == "water_nozzle")
            settings_.water_nozzle = kWaterNozzleRange.clamp(v.get<double>(), size);
        else if (k2 == "water_jet")
            settings_.water_jet = kWaterJetRange.clamp(v.get<double>(), size);
        else if (k2 == "water_shower")
            settings_.water_shower = kWaterShowerRange.clamp(v.get<double>(), size);
        else if (k2 == "pour_volume")
            settings_.pour_volume = kPourVolumeRange.clamp(v.get<double>(), size);
        else if (k2 == "brush_strength")
            settings_.brush_strength = kBrushStrengthRange.clamp(v.get<double>(), size);
        else if (k2 == "brush_blend")
            settings_.brush_blend = kBrushBlendRange.clamp(v.get<double>(), size);
        else if (k2 == "falloff")
            set_falloff(v.get<std::string>());
        else if (k2 == "simplify_tolerance")
            doc_.context().settings.simplify.tolerance = settings_.simplify_tolerance =
                kSimplifyToleranceRange.clamp(v.get<double>(), size);
        else if (k2 == "steps")
            settings_.erosion_steps =
                static_cast<int>(kErosionStepsRange.clamp(v.get<int>(), size));
        else if (k2 == "relocation_radius")
            settings_.relocation_radius = kRelocationRadiusRange.clamp(v.get<double>(), size);
        else if (k2 == "physics")
            set_physics(v.get<std::string>());
        else if (k2 == "slope_rule")
            set_slope_rule(v.get<std::string>());
        else if (k2 == "scene_path")
            set_scene_field(v.get<std::string>());
        else if (k2 == "import_path")
            set_import_field(v.get<std::string>());
        else if (k2 == "export_path")
            set_export_field(v.get<std::string>());
        else
            throw std::runtime_error("script: unknown setting '" + k2 + "'");
    }
}

void App::queue_pointer_op(const std::string& kind, const nlohmann::json& op) {
    int w = 0, h = 0;
    window_->window_size(w, h);
    auto px = [&](const nlohmann::json& p) {
        return std::pair<double, double>{p.at(0).get<double>() * w, p.at(1).get<double>() * h};
    };
    const std::string b = op.value("button", "left");
    const int button = b == "right"    ? GLFW_MOUSE_BUTTON_RIGHT
                       : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE
                                       : GLFW_MOUSE_BUTTON_LEFT;
    auto step = [this](std::function<void()> send) {
        input_steps_.push_back([send = std::move(send)] {
            send();
            return true;
        });
    };
    if (kind == "tool") {
        // Through the tool's key, as an artist picks it.
        const std::string name = op.at("name").get<std::string>();
        const std::optional<int> tool = tool_named(name);
        if (!tool) throw std::runtime_error("script: unknown tool '" + name + "'");
        queue_key(kTools[*tool].key, false);
    } else if (kind == "click" && op.contains("widget")) {
        queue_widget_click(op.at("widget").get<std::string>(), op.value("ctrl", false), {});
    } else if (kind == "click") {
        const auto p = px(op.at("at"));
        queue_click([p] { return p; }, button, op.value("ctrl", false));
    } else if (kind == "drag") {
        const auto& path = op.at("path");
        if (path.size() < 2) throw std::runtime_error("script: a drag needs two points");
        const int steps = std::max(1, op.value("steps", 20));
        std::vector<std::pair<double, double>> pts;
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
            const auto a = px(path[i]), c = px(path[i + 1]);
            for (int s = 0; s < steps; ++s) {
                const double t = static_cast<double>(s) / steps;
                pts.push_back(
                    {a.first + t * (c.first - a.first), a.second + t * (c.second - a.second)});
            }
        }
        pts.push_back(px(path.back()));
        // Pointer to the start, button down, the motion (every event delivered before the
        // next frame, as a quick hand's), button up.
        step([this, p = pts[0]] { x_input_->move_to(p.first, p.second); });
        step([this, button] { x_input_->button(button, true); });
        step([this, pts] {
            for (std::size_t i = 1; i < pts.size(); ++i)
                x_input_->move_to(pts[i].first, pts[i].second);
        });
        step([this, button] { x_input_->button(button, false); });
    } else if (kind == "press" || kind == "move" || kind == "hover") {
        if (op.contains("widget")) {
            const std::string name = op.at("widget").get<std::string>();
            auto waited = std::make_shared<int>(0);
            input_steps_.push_back([this, name, waited] {
                const auto c = widget_centre(name);
                if (!c && ++*waited > kWidgetWaitFrames)
                    throw std::runtime_error("script: no control '" + name + "' on screen");
                if (c) x_input_->move_to(c->first, c->second);
                return c.has_value();
            });
        } else {
            const auto p = px(op.at("at"));
            step([this, p] { x_input_->move_to(p.first, p.second); });
        }
        if (kind == "press") step([this] { x_input_->button(GLFW_MOUSE_BUTTON_LEFT, true); });
    } else if (kind == "release") {
        step([this] { x_input_->button(GLFW_MOUSE_BUTTON_LEFT, false); });
    } else if (kind == "key") {
        queue_key(glfw_key_named(op.at("key").get<std::string>()), op.value("ctrl", false));
    } else if (kind == "type") {
        queue_typing(op.at("text").get<std::string>());
    } else if (kind == "scroll") {
        const long clicks = std::lround(op.at("steps").get<double>());
        step([this, clicks] {
            for (long i = 0; i < std::labs(clicks); ++i)
                x_input_->wheel(clicks > 0);
        });
    } else if (kind == "close") {
        step([this] { x_input_->request_close(); });
    }
}

void App::queue_prompt_op(const std::string& kind, const nlohmann::json& op) {
    const std::string choice = op.at("choice").get<std::string>();
    if (kind == "recovery") {
        if (choice != "recover" && choice != "discard")
            throw std::runtime_error("script: recovery choice must be recover or discard");
        queue_widget_click(choice == "recover" ? "recovery/Recover" : "recovery/Discard", false,
                           "there is no autosave to recover or discard");
    } else if (kind == "discard") {
        if (choice != "save" && choice != "discard" && choice != "cancel")
            throw std::runtime_error("script: discard choice must be save, discard or cancel");
        queue_widget_click(choice == "save"      ? "unsaved/Save"
                           : choice == "discard" ? "unsaved/Discard"
                                                 : "unsaved/Cancel",
                           false, "no unsaved edits wait to be discarded");
    } else {
        if (choice != "replace" && choice != "cancel")
            throw std::runtime_error("script: overwrite choice must be replace or cancel");
        queue_widget_click(choice == "replace" ? "overwrite/Replace" : "overwrite/Cancel", false,
                           "no save waits to replace a file");
    }
}

void App::run_document_op(const std::string& kind, const nlohmann::json& op) {
    if (kind == "panels") {
        open_panels_ = op.at("open").get<bool>();
    } else if (kind == "camera") {
        // Absolute orbit angles (radians) and a zoom in wheel steps from frame-to-fit, which
        // frames the terrain as seen from those angles.
        camera_.yaw = op.value("yaw", camera_.yaw);
        camera_.pitch = std::clamp(op.value("pitch", camera_.pitch), OrbitCamera::kMinPitch,
                                   OrbitCamera::kMaxPitch);
        frame_terrain();
        camera_.zoom(op.value("zoom", 0.0));
    } else if (kind == "resize") {
        const int nw = op.at("size").at(0).get<int>(), nh = op.at("size").at(1).get<int>();
        if (nw < 64 || nh < 64 || nw > 8192 || nh > 8192)
            throw std::runtime_error("script: resize wants 64..8192 pixels a side");
        glfwSetWindowSize(window_->glfw(), nw, nh);
    } else if (kind == "haptics") {
        // Connects the simulated pen (as the panel's Connect button does) or disconnects.
        if (op.value("connect", true)) {
            haptics_ = std::make_unique<HapticsSession>(HapticDeviceKind::SimulatedSpring,
                                                        op.value("rate", 1000.0), 0,
                                                        cursor_.value_or(Vec3{0.5, 0.5, 0.1}));
        } else {
            haptics_.reset();
        }
    } else if (kind == "settle") {
        // Frames until the sand rests and the undo level it made is closed.
        const int most = op.value("frames", 600);
        auto waited = std::make_shared<int>(0);
        input_steps_.push_back([this, most, waited] {
            if (!erosion_runs() ||
                (!sculpting_.wants_to_erode(doc_) && sculpting_.open_level().empty()))
                return true;
            if (++*waited > most)
                throw std::runtime_error("script: the sand did not rest within " +
                                         std::to_string(most) + " frames");
            return false;
        });
    } else if (kind == "wait" || kind == "erode") {
        if (kind == "erode" && !erosion_runs()) toggle_erosion();
        script_wait_ = op.value("frames", 1);
    } else if (kind == "material") {
        // As the Materials panel: angles in degrees, linear RGB colour.
        const int index = op.value("index", settings_.material);
        if (index < 0 || index >= static_cast<int>(doc_.materials().size()))
            throw std::runtime_error("script: there is no material " + std::to_string(index));
        Material m = doc_.materials().all()[static_cast<std::size_t>(index)];
        constexpr double kDeg = 3.14159265358979323846 / 180.0;
        if (op.contains("repose_dry")) m.repose_dry = op["repose_dry"].get<double>() * kDeg;
        if (op.contains("repose_moist")) m.repose_wet = op["repose_moist"].get<double>() * kDeg;
        m.repose_wet = std::max(m.repose_wet, m.repose_dry);
        if (op.contains("colour")) {
            for (std::size_t c = 0; c < 3; ++c)
                m.colour[c] = std::clamp(op["colour"].at(c).get<float>(), 0.0f, 1.0f);
        }
        edit_material(index, m);
    } else if (kind == "jobs" || kind == "job" || kind == "cancel_job" || kind == "resume_job") {
        run_job_op(kind, op);
    } else if (kind == "drop") {
        drop_files(op.at("paths").get<std::vector<std::string>>());
    } else if (kind == "stage_times") {
        // Earlier frames' real times go, so the medians are the forced time from the next frame.
        times_ = StageTimes{};
        times_.forced_ms = op.at("ms").get<double>();
    } else if (kind == "save_settings") {
        save_settings_reporting();  // what the interactive loop does after a panel change
    } else if (kind == "save") {
        // As Save does, on a worker; but a script cannot go on past a save that failed: a bad
        // name fails it here, a failed write when the job ends (poll_job).
        const std::filesystem::path path = op.at("path").get<std::string>();
        if (const std::optional<std::string> problem = Document::save_name_problem(path))
            throw std::runtime_error("save failed: " + *problem);
        save(path);
        script_job_must_succeed_ = busy();
    } else if (kind == "export") {
        sculpting_.close_level(doc_);
        doc_.export_to(op.at("path").get<std::string>());
    } else if (kind == "autosave") {
        // A script that asks for an autosave gets autosaving as an interactive session has it
        // (otherwise scripted runs leave no autosave files behind).
        autosave_in_script_ = true;
        sculpting_.close_level(doc_);
        keep_unsaved_edits();
    } else {
        throw std::runtime_error("script: unknown op '" + kind + "'");
    }
}

void App::run_job_op(const std::string& kind, const nlohmann::json& op) {
    if (kind == "jobs") {
        script_waits_for_jobs_ = op.value("wait", true);
        if (op.contains("pause_at"))
            job_pause_at_ = op.at("pause_at").get<double>();
        else
            job_pause_at_.reset();
    } else if (kind == "job") {
        const std::string until = op.value("until", "done");
        if (until != "paused" && until != "done")
            throw std::runtime_error("script: a job op waits until paused or done");
        const int most = op.value("frames", 600);
        auto waited = std::make_shared<int>(0);
        input_steps_.push_back([this, until, most, waited] {
            if (until == "done" ? !busy() : busy() && job_->paused()) return true;
            if (until == "paused" && !busy())
                throw std::runtime_error("script: the job ended before its pause point");
            if (++*waited > most)
                throw std::runtime_error("script: the job was not " + until + " within " +
                                         std::to_string(most) + " frames");
            return false;
        });
    } else if (kind == "cancel_job") {
        if (busy())
            queue_widget_click("job/Cancel", false, "no job runs");
        else
            queue_widget_click("settle/Stop", false, "the sand is not settling to rest");
    } else if (busy()) {
        job_->resume();
    }
}

}  // namespace sandtin::editor
