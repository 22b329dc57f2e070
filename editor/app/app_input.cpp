// Mouse and keyboard: camera moves, tools along the stroke, undo and redo.

#include "app.hpp"

namespace sandtin::editor {

// ---- Input ----------------------------------------------------------------------------------

std::optional<Vec3> App::pick(double x, double y) const {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const Ray ray = camera_.pixel_ray(x, y, w, h);
    const Rect d = doc_.tin->domain();
    const double step = std::max(d.width(), d.height()) / 2000.0;
    const auto hit = pick_terrain(*doc_.tin, ray, d.centre(), step, camera_.distance * 4.0);
    if (!hit) return std::nullopt;
    return hit->point;
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

void App::tool_at(Vec3 p) {
    const auto t0 = Clock::now();
    const ToolEntry& t = kTools[settings_.tool];
    const Vec2 xy{p.x, p.y};
    switch (t.kind) {
        case ToolKind::Stamp: {
            if (!sampler_) {
                active_tool_ = build_tool();
                sampler_.emplace(settings_.stroke_spacing_ratio * active_tool_->radius());
            }
            StrokeSettings ss;
            ss.depth = settings_.tool_depth;
            ss.follow_path = settings_.follow_path;
            ss.angle = settings_.tool_angle * 3.14159265358979 / 180.0;
            if (std::getenv("SANDTIN_EDITOR_TRACE") != nullptr)
                std::fprintf(stderr, "sandtin-editor: stroke point %.4f %.4f\n", xy.x, xy.y);
            for (const StrokeSample& s : sampler_->add_point(xy)) {
                const ToolPlacement at =
                    placement_for(*doc_.tin, *active_tool_, s, ss, &doc_.context->hint);
                const StampReport r =
                    stamp(*doc_.tin, *active_tool_, at, *doc_.context, s.direction);
                if (const std::optional<std::string> w = lost_extrusion_warning(r)) report(*w);
                last_heading_ = at.angle;
            }
            open_level_ = std::string("stroke (") + t.label + ")";
            break;
        }
        case ToolKind::Brush: {
            if (last_dab_ && distance(*last_dab_, xy) < settings_.tool_radius * 0.25) break;
            if (std::getenv("SANDTIN_EDITOR_TRACE") != nullptr)
                std::fprintf(stderr, "sandtin-editor: dab %.4f %.4f\n", xy.x, xy.y);
            // Flatten levels the whole stroke to the surface where it began.
            if (!last_dab_) flatten_level_ = p.z;
            BrushSettings b;
            b.kind = t.brush;
            b.radius = settings_.tool_radius;
            const bool height_brush = t.brush == BrushKind::Raise || t.brush == BrushKind::Lower;
            b.strength = height_brush ? settings_.brush_strength : settings_.brush_blend;
            b.falloff = falloff_named(settings_.brush_falloff).value_or(Falloff::Smooth);
            b.material = static_cast<std::uint16_t>(settings_.material);
            b.moisture = doc_.materials.at(b.material).default_moisture;
            if (t.brush == BrushKind::Flatten) b.flatten_to = flatten_level_;
            apply_brush(*doc_.tin, xy, b, *doc_.context);
            last_dab_ = xy;
            open_level_ = std::string("brush (") + t.label + ")";
            break;
        }
        case ToolKind::Pour:
        case ToolKind::Remove:
            pour_at(xy);
            break;
    }
    tool_ms_ += ms_since(t0);
    physics_kick_ = true;
}

void App::pour_at(Vec2 xy) {
    if (pour_flow_) {
        for (Vec2 at : pour_flow_->move(xy))
            pour_dab(at);
        return;
    }
    // The dabs along a drag are spaced as the script's pour path spaces its points: half the
    // pour disc's radius.
    pour_flow_.emplace(0.5 * pour_radius());
    pour_removes_ = kTools[settings_.tool].kind == ToolKind::Remove;
    pour_clock_ = Clock::now();
    for (Vec2 at : pour_flow_->press(xy))
        pour_dab(at);
}

void App::pour_dab(Vec2 at) {
    PourSettings ps;
    ps.radius = pour_radius();
    const PourReport r = pour_removes_
                             ? remove_sand(*doc_.tin, at, settings_.pour_volume, ps, *doc_.context)
                             : pour_sand(*doc_.tin, at, settings_.pour_volume, ps, *doc_.context);
    pour_asked_ += settings_.pour_volume;
    pour_moved_ += r.volume;
    open_level_ = pour_removes_ ? "remove sand" : "pour";
    physics_kick_ = true;
}

void App::pour_while_held() {
    if (!pour_flow_ || !left_down_) return;
    const auto now = Clock::now();
    const double seconds = options_.scripted()
                               ? kScriptFrameSeconds
                               : std::chrono::duration<double>(now - pour_clock_).count();
    pour_clock_ = now;
    for (Vec2 at : pour_flow_->hold(seconds))
        pour_dab(at);
    tool_ms_ += ms_since(now);
}

void App::end_pour() {
    if (!pour_flow_) return;
    pour_flow_.reset();
    if (const std::optional<std::string> w =
            short_pour_warning(pour_removes_, pour_asked_, pour_moved_))
        report(*w);
    pour_asked_ = pour_moved_ = 0.0;
}

// ---- Gestures and undo levels ----------------------------------------------------------------
//
// A gesture (a stroke, a brush stroke, a pour) opens an undo level with its first edit. The
// level stays open after the button is released while the sand it disturbed slides, and closes
// when the sand rests (settle_erosion) or when anything else is about to change the document
// (end_action): one Ctrl+Z undoes one stroke with its settling, as in a sculpting program.

void App::end_gesture() {
    if (sampler_) {
        // A press that never moved has no direction: its ridge goes all around the tool.
        const bool moved = sampler_->length() > 0.0;
        for (const StrokeSample& s : sampler_->finish()) {
            StrokeSettings ss;
            ss.depth = settings_.tool_depth;
            ss.follow_path = settings_.follow_path;
            ss.angle = settings_.tool_angle * 3.14159265358979 / 180.0;
            const ToolPlacement at =
                placement_for(*doc_.tin, *active_tool_, s, ss, &doc_.context->hint);
            const StampReport r = stamp(*doc_.tin, *active_tool_, at, *doc_.context,
                                        moved ? std::optional<Vec2>(s.direction) : std::nullopt);
            if (const std::optional<std::string> w = lost_extrusion_warning(r))
                report(*w);
            else if (!r.applied)
                report("the stamp missed the terrain");
        }
        sampler_.reset();
    }
    end_pour();
    last_dab_.reset();
}

void App::end_action() {
    end_gesture();
    if (!open_level_.empty()) {
        if (doc_.history->record(open_level_)) {
            mark_edited();
            undo_log_.push_terrain(open_level_);
        }
        open_level_.clear();
    }
    resettling_ = false;
}

void App::abandon_gesture() {
    sampler_.reset();
    pour_flow_.reset();
    pour_asked_ = pour_moved_ = 0.0;
    left_down_ = false;
    try {
        end_action();  // what the gesture did so far is kept, as its own undo level
    } catch (const std::exception&) {
        open_level_.clear();
    }
}

void App::settle_erosion() {
    // Flat ground the sand left behind, and the refinement r_S grew where it passed, go as an
    // edit's do: detail follows the work. A removal re-triangulates its hole and shifts heights
    // to keep the volume, which can steepen an edge, so the sand settles once more before the
    // level closes; what that moves waits for the next edit's simplification, as the scripts'
    // "until_rest" does. (More rounds gain little: on a pour's flanks the settling refines
    // again at r_S what the simplification removed. Measured on a 0.1 L pour on 3 000 points,
    // r_S = 1 cm, before the refinement's vertices were queued too: 3 414 vertices without
    // it, 3 262 after one round, 3 241 after three, 3 224 after six.)
    if (!resettling_ && doc_.context->settings.simplify_after_edit) {
        const SimplifyReport simplified =
            doc_.context->simplifier.run(*doc_.tin, doc_.context->settings.simplify);
        if (simplified.removed > 0) {
            resettling_ = true;
            physics_kick_ = true;
            return;
        }
    }
    end_action();
}

// ---- Mouse and keys -----------------------------------------------------------------------

void App::mouse_button(int button, bool down, double x, double y) {
    mouse_x_ = x;
    mouse_y_ = y;
    redraw_frames_ = 3;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        if (down) {
            // The previous gesture's level closes, settled or not: this is a new one.
            end_action();
            left_down_ = true;
            if (const auto p = pick(x, y)) tool_at(*p);
        } else if (left_down_) {
            left_down_ = false;
            end_gesture();
            // Without erosion nothing settles: the level closes now.
            if (!erosion_runs()) end_action();
        }
    } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
        right_down_ = down;
    } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
        middle_down_ = down;
    }
}

void App::mouse_move(double x, double y) {
    const double dx = x - mouse_x_, dy = y - mouse_y_;
    mouse_x_ = x;
    mouse_y_ = y;
    redraw_frames_ = 3;
    if (right_down_) camera_.orbit(dx, dy);
    if (middle_down_) {
        int w = 0, h = 0;
        glfwGetWindowSize(window_, &w, &h);
        camera_.pan(dx, dy, h);
    }
    cursor_ = pick(x, y);
    if (left_down_ && cursor_) tool_at(*cursor_);
}

void App::scroll(double dy) {
    camera_.zoom(dy);
    redraw_frames_ = 3;
}

void App::key(int k, bool ctrl) {
    redraw_frames_ = 3;
    // While a prompt waits for its answer, shortcuts must not change the document under it
    // (Ctrl+O could open another scene with the recovery prompt still about the first).
    if (recovery_for_ || pending_replacement_ || pending_overwrite_) return;
    if (ctrl && k == GLFW_KEY_Z)
        undo();
    else if (ctrl && k == GLFW_KEY_Y)
        redo();
    else if (ctrl && k == GLFW_KEY_S)
        request_save(save_path());
    else if (ctrl && k == GLFW_KEY_N) {
        replace_document("New", [this] { new_document(); });
    } else if (ctrl && k == GLFW_KEY_O) {
        replace_document("Open", [this] { open_reporting(); });
    } else if (ctrl && k == GLFW_KEY_Q) {
        // As the window's close button: an untitled scene's unsaved edits are asked about.
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
    } else if (ctrl) {
        return;  // no other shortcut uses Ctrl: Ctrl+R must not pick the Raise brush
    } else if (k == GLFW_KEY_F) {
        frame_terrain();
    } else if (const std::optional<int> tool = tool_for_key(k)) {
        if (left_down_) return;  // not in the middle of a stroke
        end_gesture();
        settings_.tool = *tool;
    }
}

}  // namespace sandtin::editor
