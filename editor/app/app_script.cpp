// Scripted mode: JSON ops fed through the same handlers as the real mouse and keys.

#include "app.hpp"

namespace sandtin::editor {

// ---- Script ---------------------------------------------------------------------------------
//
// {"ops": [ {"op": "tool", "name": "Ball"} | {"op": "set", "<setting>": value, ...}
//         | {"op": "drag", "button": "left"|"right"|"middle", "path": [[fx, fy], ...], "steps": n}
//         | {"op": "click", "at": [fx, fy]} | {"op": "move", "at": [fx, fy]}
//         | {"op": "press", "at": [fx, fy]} | {"op": "release"}  (the left button held down
//            across frames: a "wait" between them holds it still, each frame counting 1/60 s)
//         | {"op": "key", "key": "z", "ctrl": true}
//         | {"op": "scroll", "steps": s} | {"op": "wait", "frames": n}
//         | {"op": "camera", "yaw": rad, "pitch": rad, "zoom": steps}
//         | {"op": "haptics", "connect": true|false, "rate": hz}
//         | {"op": "recovery", "choice": "recover"|"discard"}  (answers the autosave prompt)
//         | {"op": "discard", "choice": "save"|"discard"|"cancel"}  (answers the prompt before
//            New, Open, Import or closing drops an untitled scene's unsaved edits; "save" saves
//            to the Scene field first)
//         | {"op": "close"}  (the window's close button)
//         | {"op": "resize", "size": [w, h]}  (the window, in screen pixels)
//         | {"op": "panels", "open": true|false}  (every panel header, from the next frame)
//         | {"op": "erode", "frames": n} | {"op": "save", "path": "..."}
//         | {"op": "export", "path": "..."}  (the File panel's Export)
//         | {"op": "autosave"}  (unsaved edits to the autosave now, as on closing)
//         | {"op": "save_settings"}  (writes the settings file, as a panel change does)
//         | {"op": "material", "index": i, "repose_dry": deg, "repose_moist": deg,
//            "colour": [r, g, b]}  (the Materials panel's edit: one undo level) ] }
// "set" knows radius, depth, material, erosion, wireframe, slope, pour_volume, brush_strength
// (Raise and Lower, metres per dab), brush_blend (Smooth and Flatten, 0..1 per dab), falloff
// ("constant" | "linear" | "smooth" | "gaussian"), steps, relocation_radius,
// simplify_tolerance (metres, as the Erosion panel's slider), physics ("cpu" | "gpu", the
// Erosion panel's switch) and scene_path (typed into the File panel's Scene field).
// Positions are fractions of the window (0..1): scripts work at any --size.

void App::set_physics(const std::string& name) {
    if (name != "cpu" && name != "gpu")
        throw std::runtime_error("script: physics must be cpu or gpu, not '" + name + "'");
    if ((name == "gpu") == settings_.erosion_gpu) return;
    end_action();
    settings_.erosion_gpu = name == "gpu";
    attach_physics(true);
}

void App::set_falloff(const std::string& name) {
    if (!falloff_named(name)) {
        throw std::runtime_error(
            "script: falloff must be constant, linear, smooth or gaussian, not '" + name + "'");
    }
    settings_.brush_falloff = name;
}

void App::set_scene_field(const std::string& path) {
    if (path.size() >= sizeof(path_buf_))
        throw std::runtime_error("script: scene_path is longer than the Scene field holds");
    std::snprintf(path_buf_, sizeof(path_buf_), "%s", path.c_str());
}

void App::run_script_op(const nlohmann::json& op) {
    // Ops drive the input handlers directly, without GLFW callbacks: release as they do.
    if (haptics_) haptics_->release();
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const std::string kind = op.at("op").get<std::string>();
    auto px = [&](const nlohmann::json& p) {
        return std::pair<double, double>{p.at(0).get<double>() * w, p.at(1).get<double>() * h};
    };
    if (kind == "tool") {
        // Through the tool's key, as an artist picks it.
        const std::string name = op.at("name").get<std::string>();
        const std::optional<int> tool = tool_named(name);
        if (!tool) throw std::runtime_error("script: unknown tool '" + name + "'");
        key(kTools[*tool].key, false);
    } else if (kind == "panels") {
        open_panels_ = op.at("open").get<bool>();
    } else if (kind == "set") {
        nlohmann::json j = op;
        j.erase("op");
        for (auto& [k2, v] : j.items()) {
            if (k2 == "radius")
                settings_.tool_radius = v.get<double>();
            else if (k2 == "depth")
                settings_.tool_depth = v.get<double>();
            else if (k2 == "material")
                settings_.material = v.get<int>();
            else if (k2 == "erosion")
                settings_.erosion_running = v.get<bool>();
            else if (k2 == "wireframe")
                settings_.overlay_wireframe = v.get<bool>();
            else if (k2 == "slope")
                settings_.overlay_slope = v.get<bool>();
            else if (k2 == "pour_volume")
                settings_.pour_volume = v.get<double>();
            else if (k2 == "brush_strength")
                settings_.brush_strength = v.get<double>();
            else if (k2 == "brush_blend")
                settings_.brush_blend = std::clamp(v.get<double>(), 0.0, 1.0);
            else if (k2 == "falloff")
                set_falloff(v.get<std::string>());
            else if (k2 == "simplify_tolerance")
                doc_.context->settings.simplify.tolerance = settings_.simplify_tolerance =
                    std::max(0.0, v.get<double>());
            else if (k2 == "steps")
                settings_.erosion_steps = std::clamp(v.get<int>(), 1, 1000);
            else if (k2 == "relocation_radius")
                settings_.relocation_radius = v.get<double>();
            else if (k2 == "physics")
                set_physics(v.get<std::string>());
            else if (k2 == "scene_path")
                set_scene_field(v.get<std::string>());
            else
                throw std::runtime_error("script: unknown setting '" + k2 + "'");
        }
    } else if (kind == "drag" || kind == "click") {
        const std::string b = op.value("button", "left");
        const int button = b == "right"    ? GLFW_MOUSE_BUTTON_RIGHT
                           : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE
                                           : GLFW_MOUSE_BUTTON_LEFT;
        std::vector<std::pair<double, double>> pts;
        if (kind == "click") {
            pts.push_back(px(op.at("at")));
        } else {
            const auto& path = op.at("path");
            if (path.size() < 2) throw std::runtime_error("script: a drag needs two points");
            const int steps = std::max(1, op.value("steps", 20));
            for (std::size_t i = 0; i + 1 < path.size(); ++i) {
                const auto a = px(path[i]), c = px(path[i + 1]);
                for (int s = 0; s < steps; ++s) {
                    const double t = static_cast<double>(s) / steps;
                    pts.push_back(
                        {a.first + t * (c.first - a.first), a.second + t * (c.second - a.second)});
                }
            }
            pts.push_back(px(path.back()));
        }
        mouse_move(pts[0].first, pts[0].second);
        mouse_button(button, true, pts[0].first, pts[0].second);
        for (std::size_t i = 1; i < pts.size(); ++i)
            mouse_move(pts[i].first, pts[i].second);
        mouse_button(button, false, pts.back().first, pts.back().second);
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
        glfwSetWindowSize(window_, nw, nh);
    } else if (kind == "recovery") {
        const std::string choice = op.at("choice").get<std::string>();
        if (choice != "recover" && choice != "discard")
            throw std::runtime_error("script: recovery choice must be recover or discard");
        answer_recovery(choice == "recover");
    } else if (kind == "close") {
        glfwSetWindowShouldClose(window_, GLFW_TRUE);  // as the window's close button does
    } else if (kind == "discard") {
        const std::string choice = op.at("choice").get<std::string>();
        if (choice != "save" && choice != "discard" && choice != "cancel")
            throw std::runtime_error("script: discard choice must be save, discard or cancel");
        answer_discard(choice == "save"      ? DiscardChoice::Save
                       : choice == "discard" ? DiscardChoice::Discard
                                             : DiscardChoice::Cancel);
    } else if (kind == "haptics") {
        // Connects the simulated pen (as the panel's Connect button does) or disconnects.
        if (op.value("connect", true)) {
            haptics_ = std::make_unique<HapticsSession>(HapticDeviceKind::SimulatedSpring,
                                                        op.value("rate", 1000.0), 0,
                                                        cursor_.value_or(Vec3{0.5, 0.5, 0.1}));
        } else {
            haptics_.reset();
        }
    } else if (kind == "press") {
        const auto p = px(op.at("at"));
        mouse_move(p.first, p.second);
        mouse_button(GLFW_MOUSE_BUTTON_LEFT, true, p.first, p.second);
    } else if (kind == "release") {
        mouse_button(GLFW_MOUSE_BUTTON_LEFT, false, mouse_x_, mouse_y_);
    } else if (kind == "move") {
        const auto p = px(op.at("at"));
        mouse_move(p.first, p.second);
    } else if (kind == "key") {
        const std::string k = op.at("key").get<std::string>();
        if (k.size() != 1) throw std::runtime_error("script: key must be one character");
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(k[0])));
        key(c >= '0' && c <= '9' ? GLFW_KEY_0 + (c - '0') : GLFW_KEY_A + (c - 'A'),
            op.value("ctrl", false));
    } else if (kind == "scroll") {
        scroll(op.at("steps").get<double>());
    } else if (kind == "wait" || kind == "erode") {
        if (kind == "erode") settings_.erosion_running = true;
        script_wait_ = op.value("frames", 1);
    } else if (kind == "material") {
        // As the Materials panel: angles in degrees, linear RGB colour.
        const int index = op.value("index", settings_.material);
        if (index < 0 || index >= static_cast<int>(doc_.materials.size()))
            throw std::runtime_error("script: there is no material " + std::to_string(index));
        Material m = doc_.materials.all()[static_cast<std::size_t>(index)];
        constexpr double kDeg = 3.14159265358979323846 / 180.0;
        if (op.contains("repose_dry")) m.repose_dry = op["repose_dry"].get<double>() * kDeg;
        if (op.contains("repose_moist")) m.repose_wet = op["repose_moist"].get<double>() * kDeg;
        m.repose_wet = std::max(m.repose_wet, m.repose_dry);
        if (op.contains("colour")) {
            for (std::size_t c = 0; c < 3; ++c)
                m.colour[c] = std::clamp(op["colour"].at(c).get<float>(), 0.0f, 1.0f);
        }
        edit_material(index, m);
    } else if (kind == "save_settings") {
        save_settings_reporting();  // what the interactive loop does after a panel change
    } else if (kind == "save") {
        save(op.at("path").get<std::string>());
    } else if (kind == "export") {
        export_to(op.at("path").get<std::string>());
    } else if (kind == "autosave") {
        // A script that asks for an autosave gets autosaving as an interactive session has it
        // (otherwise scripted runs leave no autosave files behind).
        autosave_in_script_ = true;
        end_action();
        keep_unsaved_edits();
    } else {
        throw std::runtime_error("script: unknown op '" + kind + "'");
    }
}

}  // namespace sandtin::editor
