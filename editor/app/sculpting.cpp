#include "sculpting.hpp"

#include <algorithm>
#include <numbers>

#include "tool_palette.hpp"
#include "tools/brushes.hpp"
#include "tools/falloff.hpp"
#include "tools/sand.hpp"
#include "tools/tool_json.hpp"
#include "util/elapsed_ms.hpp"

namespace sandtin::editor {

namespace {

using Clock = std::chrono::steady_clock;

double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

}  // namespace

Tool build_tool(const EditorSettings& settings) {
    ToolSpec spec =
        scaled_tool_spec(load_tool_asset(kTools[settings.tool].asset), settings.scene_size);
    if (sized_by_slider(spec)) spec.radius = settings.tool_radius;
    spec.extrude = settings.extrude;
    return Tool::build(spec);
}

// ---- The gesture --------------------------------------------------------------------------

void Sculpting::press(Document& doc, Vec3 point, const EditorSettings& settings) {
    close_level(doc);  // the previous edit's level closes, settled or not: this is a new one
    pressed_ = true;
    apply(doc, point, settings);
}

void Sculpting::drag(Document& doc, Vec3 point, const EditorSettings& settings) {
    if (pressed_) apply(doc, point, settings);
}

void Sculpting::hold(Document& doc, double seconds, const EditorSettings& settings) {
    // The nozzle gives water as the water flows (flow_water), not per hold.
    if (!pressed_ || !pour_flow_) return;
    const auto t0 = Clock::now();
    for (Vec2 at : pour_flow_->hold(seconds))
        pour_dab(doc, at, settings);
    tool_ms_ += elapsed_ms(t0);
    kick_ = true;
}

void Sculpting::release(Document& doc, bool erosion_runs) {
    if (!pressed_) return;
    pressed_ = false;
    end_gesture(doc);
    if (!erosion_runs) close_level(doc);  // without erosion nothing settles
}

void Sculpting::apply(Document& doc, Vec3 point, const EditorSettings& settings) {
    const auto t0 = Clock::now();
    const ToolEntry& t = kTools[settings.tool];
    switch (t.kind) {
        case ToolKind::Stamp:
            stamp_at(doc, {point.x, point.y}, settings);
            open_level_ = std::string("stroke (") + t.label + ")";
            break;
        case ToolKind::Brush:
            brush_at(doc, point, settings);
            break;
        case ToolKind::Pour:
        case ToolKind::Remove:
            pour_at(doc, {point.x, point.y}, settings);
            break;
        case ToolKind::Water:
            nozzle_ = Vec2{point.x, point.y};  // flow_water() pours while it is held
            open_level_ = "water";
            break;
        case ToolKind::Rain:
            shower_ = Vec2{point.x, point.y};  // flow_water() rains while it is held
            open_level_ = "water";
            break;
    }
    tool_ms_ += elapsed_ms(t0);
    kick_ = true;
}

void Sculpting::stamp_at(Document& doc, Vec2 xy, const EditorSettings& settings) {
    if (!stroke_) {
        tool_.emplace(build_tool(settings));
        StrokeSettings ss;
        ss.spacing = settings.stroke_spacing_ratio * tool_->radius();
        ss.depth = settings.tool_depth;
        ss.follow_path = settings.follow_path;
        ss.angle = radians(settings.tool_angle);
        stroke_.emplace(*tool_, ss);
    }
    note_stamps(stroke_->add_point(doc.tin(), xy, doc.context()));
}

void Sculpting::note_stamps(const std::vector<StrokeStamp>& stamps) {
    for (const StrokeStamp& s : stamps) {
        heading_ = s.placement.angle;
        if (const std::optional<std::string> w = lost_extrusion_warning(s.report))
            messages_.push_back(*w);
        else if (!s.report.applied)
            messages_.push_back("the stamp missed the terrain");
    }
}

void Sculpting::brush_at(Document& doc, Vec3 point, const EditorSettings& settings) {
    const ToolEntry& t = kTools[settings.tool];
    const Vec2 xy{point.x, point.y};
    // Dabs a quarter of the radius apart, however fast the mouse.
    if (last_dab_ && distance(*last_dab_, xy) < settings.tool_radius * 0.25) return;
    // Flatten levels the whole stroke to the surface where it began.
    if (!last_dab_) flatten_level_ = point.z;
    BrushSettings b;
    b.kind = t.brush;
    b.radius = settings.tool_radius;
    const bool height_brush = t.brush == BrushKind::Raise || t.brush == BrushKind::Lower;
    b.strength = height_brush ? settings.brush_strength : settings.brush_blend;
    b.falloff = falloff_named(settings.brush_falloff).value_or(Falloff::Smooth);
    b.material = static_cast<std::uint16_t>(settings.material);
    b.moisture = doc.materials().at(b.material).default_moisture;
    if (t.brush == BrushKind::Flatten) b.flatten_to = flatten_level_;
    apply_brush(doc.tin(), xy, b, doc.context());
    last_dab_ = xy;
    open_level_ = std::string("brush (") + t.label + ")";
}

void Sculpting::pour_at(Document& doc, Vec2 xy, const EditorSettings& settings) {
    if (pour_flow_) {
        for (Vec2 at : pour_flow_->move(xy))
            pour_dab(doc, at, settings);
        return;
    }
    // The dabs along a drag are spaced as the script's pour path spaces its points: half the
    // pour disc's radius (which is half the Size).
    pour_flow_.emplace(0.25 * settings.tool_radius);
    pour_removes_ = kTools[settings.tool].kind == ToolKind::Remove;
    for (Vec2 at : pour_flow_->press(xy))
        pour_dab(doc, at, settings);
}

void Sculpting::pour_dab(Document& doc, Vec2 at, const EditorSettings& settings) {
    PourSettings ps;
    ps.radius = 0.5 * settings.tool_radius;
    const PourReport r = pour_removes_
                             ? remove_sand(doc.tin(), at, settings.pour_volume, ps, doc.context())
                             : pour_sand(doc.tin(), at, settings.pour_volume, ps, doc.context());
    pour_asked_ += settings.pour_volume;
    pour_moved_ += r.volume;
    open_level_ = pour_removes_ ? "remove sand" : "pour";
}

void Sculpting::end_pour() {
    if (!pour_flow_) return;
    pour_flow_.reset();
    if (const std::optional<std::string> w =
            short_pour_warning(pour_removes_, pour_asked_, pour_moved_))
        messages_.push_back(*w);
    pour_asked_ = pour_moved_ = 0.0;
}

void Sculpting::end_gesture(Document& doc) {
    if (stroke_) {
        // A press that never moved stamps now, without a direction: its ridge goes all round.
        note_stamps(stroke_->finish(doc.tin(), doc.context()));
        stroke_.reset();
        tool_.reset();
    }
    end_pour();
    last_dab_.reset();
    nozzle_.reset();
    shower_.reset();
}

// ---- Water --------------------------------------------------------------------------------

LiveWaterSettings water_settings(const EditorSettings& settings) {
    LiveWaterSettings w;
    w.flowing = settings.water_flowing;
    w.rain_mm_per_hour = settings.water_rain;
    w.evaporation_mm_per_hour = settings.water_evaporation;
    w.erode = settings.water_erode;
    w.detail = settings.water_detail;
    w.open = {settings.water_open_west, settings.water_open_east, settings.water_open_south,
              settings.water_open_north};
    return w;
}

LiveWaterFrame Sculpting::flow_water(Document& doc, const EditorSettings& settings, double seconds,
                                     double budget_ms) {
    LiveWater& water = doc.water();
    if (nozzle_) water.add_nozzle({*nozzle_, 1000.0 * settings.water_nozzle, settings.water_jet});
    if (shower_) water.add_shower({settings.water_shower, *shower_, settings.tool_radius});
    const LiveWaterFrame frame = water.advance(seconds, water_settings(settings), budget_ms);
    // Ground the water left is simplified as an edit's is (the simplifier leaves wet ground
    // alone): the detail added under the water goes once it is dry and planar again.
    const std::vector<VertexId> dried = water.take_dried();
    if (!dried.empty()) {
        doc.context().simplifier.enqueue(dried);
        kick_ = true;  // the erosion's settle runs the simplifier
    }
    if (frame.written > 0 || frame.wetted > 0 || frame.eroded > 0) {
        if (open_level_.empty()) open_level_ = "water";
        // Wet sand stands at another angle, and the banks a stream cut may be too steep.
        kick_ = kick_ || frame.wetted > 0 || frame.eroded > 0;
    }
    // A level of water alone closes once the water rests (or has dried) and no gesture holds it.
    if (open_level_ == "water" && !pressed_ && water.idle(water_settings(settings)) &&
        doc.solver().at_rest())
        close_level(doc);
    return frame;
}

// ---- The undo level -----------------------------------------------------------------------

void Sculpting::close_level(Document& doc) {
    end_gesture(doc);
    pressed_ = false;
    if (!open_level_.empty()) doc.record_level(open_level_);
    open_level_.clear();
    resettling_ = false;
}

void Sculpting::abandon(Document& doc) {
    stroke_.reset();
    tool_.reset();
    pour_flow_.reset();
    pour_asked_ = pour_moved_ = 0.0;
    try {
        close_level(doc);  // what the gesture did so far is kept, as its own undo level
    } catch (const std::exception&) {
        open_level_.clear();
    }
    pressed_ = false;
}

void Sculpting::reset() {
    stroke_.reset();
    tool_.reset();
    pour_flow_.reset();
    pour_asked_ = pour_moved_ = 0.0;
    last_dab_.reset();
    open_level_.clear();
    resettling_ = false;
    pressed_ = false;
    kick_ = true;
}

// ---- The erosion it set off ---------------------------------------------------------------

ErosionFrame Sculpting::erode(Document& doc, const EditorSettings& settings, double budget_ms) {
    ErosionFrame frame;
    RelaxationSolver& solver = doc.solver();
    // The solver learns about edits when it steps (its journal reader): an edit kicks it.
    if (!kick_ && solver.at_rest()) return frame;
    kick_ = false;
    const auto t0 = Clock::now();
    frame.ran = true;
    solver.settings().parameters.relocation_radius = settings.relocation_radius;
    // Clamped: a hand-edited settings file must not stop the physics.
    solver.settings().parameters.settle_margin =
        std::clamp(settings.settle_margin, 0.0, kMaxSettleMargin);
    solver.settings().parameters.rule =
        settings.slope_rule == "edge" ? SlopeRule::Edge : SlopeRule::Face;
    // Up to the chosen iterations, but within a time budget so the editor stays responsive
    // while a large region slides. The GPU solver batches the iterations into few
    // submissions itself, each followed by the read-back of the heights into the TIN.
    if (solver.device() == SolverDevice::Gpu) {
        solver.step(settings.erosion_steps, &frame.changed);
    } else {
        for (int i = 0; i < settings.erosion_steps; ++i) {
            solver.step(1, &frame.changed);
            if (solver.at_rest() || elapsed_ms(t0) > budget_ms) break;
        }
    }
    frame.active = solver.active_count();
    std::sort(frame.changed.begin(), frame.changed.end());
    frame.changed.erase(std::unique(frame.changed.begin(), frame.changed.end()),
                        frame.changed.end());
    // What the sand moved is simplified once it rests, as an edit's vertices are.
    doc.context().simplifier.enqueue(frame.changed);
    // Sand the erosion moved belongs to the open level (the gesture that disturbed it), or
    // makes a level of its own.
    if (!frame.changed.empty() && open_level_.empty()) open_level_ = Document::kErosionLevel;
    if (solver.at_rest() && !open_level_.empty() && !pressed_) settle(doc);
    frame.ms = elapsed_ms(t0);
    return frame;
}

void Sculpting::settle(Document& doc) {
    // Flat ground the sand left behind, and the refinement r_S grew where it passed, go as an
    // edit's do: detail follows the work. A removal re-triangulates its hole and shifts heights
    // to keep the volume, which can steepen an edge, so the sand settles once more before the
    // level closes; what that moves waits for the next edit's simplification, as the scripts'
    // "until_rest" does. (More rounds gain little: on a pour's flanks the settling refines
    // again at r_S what the simplification removed. Measured on a 0.1 L pour on 3 000 points,
    // r_S = 1 cm, before the refinement's vertices were queued too: 3 414 vertices without
    // it, 3 262 after one round, 3 241 after three, 3 224 after six.)
    SculptContext& context = doc.context();
    if (!resettling_ && context.settings.simplify_after_edit) {
        const SimplifyReport simplified =
            context.simplifier.run(doc.tin(), context.settings.simplify);
        if (simplified.removed > 0) {
            resettling_ = true;
            kick_ = true;  // the solver looks at the removals on the next frame
            return;
        }
    }
    close_level(doc);
}

// ---- Read-outs ----------------------------------------------------------------------------

std::vector<std::string> Sculpting::take_messages() {
    std::vector<std::string> out;
    out.swap(messages_);
    return out;
}

double Sculpting::take_tool_ms() {
    const double ms = tool_ms_;
    tool_ms_ = 0.0;
    return ms;
}

}  // namespace sandtin::editor
