#include "io/script.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <set>
#include <span>
#include <sstream>

#include "io/scene_materials.hpp"
#include "io/script_lines.hpp"
#include "io/session_file.hpp"
#include "physics/sand_physics.hpp"
#include "physics/settle_by_projection.hpp"
#include "physics/settle_fitted_to_kinks.hpp"
#include "tin/flat_bedrock.hpp"
#include "tools/falloff.hpp"
#include "tools/stamp.hpp"
#include "tools/tool_json.hpp"
#include "util/elapsed_ms.hpp"
#include "util/json_document.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

namespace {

Falloff parse_falloff(JsonFields& f, const char* fallback) {
    // choice() has checked the name against the list.
    return *falloff_named(f.choice("falloff", fallback, kFalloffNames));
}

/// The tool of a stamp or stroke. "extrude" may stand on the operation, as a shorthand for the
/// tool's own field (where the README first put it, and where an artist reaching for "a stroke
/// that extrudes" looks); given in both places it must agree. extrusion_width stays the tool's.
std::shared_ptr<const Tool> parse_tool(JsonFields& f, const std::filesystem::path& base_dir) {
    const nlohmann::json& t = f.required("tool");
    ToolSpec spec = parse_tool_spec(t, base_dir, f.context() + ": tool");
    if (f.has("extrude")) {
        const bool on_op = f.boolean("extrude", false);
        const auto in_tool = t.find("extrude");
        if (in_tool != t.end() && in_tool->is_boolean() && in_tool->get<bool>() != on_op) {
            f.fail(std::string("field 'extrude' is ") + (on_op ? "true" : "false") +
                   " on the operation but 'tool.extrude' is " + (on_op ? "false" : "true") +
                   "; give it in one place");
        }
        spec.extrude = on_op;
    }
    if (f.has("extrusion_width")) {
        f.fail_field("extrusion_width", "is a field of the tool: put it in \"tool\"");
    }
    try {
        return std::make_shared<const Tool>(Tool::build(spec));
    } catch (const std::exception& e) {
        f.fail_field("tool", std::string("is invalid: ") + e.what());
    }
}

/// A height or a depth (m), within the kMaxHeight a terrain may reach.
double height_field(JsonFields& f, const std::string& key, double fallback) {
    return f.in_range(key, fallback, -kMaxHeight, kMaxHeight);
}

/// Depth fields: "depth" (metres below the terrain) or "bottom" (absolute height), not both.
void parse_depth(JsonFields& f, DepthMode& mode, double& value) {
    if (f.has("depth") && f.has("bottom")) f.fail("give either 'depth' or 'bottom', not both");
    if (f.has("bottom")) {
        mode = DepthMode::Absolute;
        f.required("bottom");
        value = height_field(f, "bottom", 0.0);
    } else {
        mode = DepthMode::Relative;
        value = height_field(f, "depth", 0.0);
    }
}

/// Fails on the "spacing" field when a path of `length` metres would take more placements than
/// kMaxPlacementsPerOperation, before any of them is computed.
void check_placement_count(JsonFields& f, double length, double spacing) {
    const double count = length / spacing;
    if (!(count <= kMaxPlacementsPerOperation)) {
        std::ostringstream what;
        what << "of " << spacing << " m along a " << length << " m path asks for ";
        if (count < 1e15) {
            what << static_cast<long long>(count);
        } else {
            what << count;
        }
        what << " placements, more than the " << static_cast<long>(kMaxPlacementsPerOperation)
             << " one operation allows; use a larger spacing or split the path";
        f.fail_field("spacing", what.str());
    }
}

double path_length(std::span<const Vec2> path) {
    double length = 0.0;
    for (std::size_t k = 1; k < path.size(); ++k)
        length += distance(path[k - 1], path[k]);
    return length;
}

/// "at": one point, or "path" (+ "curve", "spacing"): points every `spacing` metres.
std::vector<Vec2> parse_points(JsonFields& f, double default_spacing) {
    if (f.has("at") == f.has("path")) f.fail("give exactly one of 'at' or 'path'");
    if (f.has("at")) return {f.point("at")};
    std::vector<Vec2> path = f.points("path", 1);
    const double spacing = f.positive("spacing", default_spacing);
    check_placement_count(f, path_length(path), spacing);
    if (f.boolean("curve", false)) path = catmull_rom(path, spacing / 4.0);
    StrokeSampler sampler(spacing);
    std::vector<Vec2> out;
    for (Vec2 p : path) {
        for (const StrokeSample& s : sampler.add_point(p))
            out.push_back(s.position);
    }
    for (const StrokeSample& s : sampler.finish())
        out.push_back(s.position);
    return out;
}

/// Physics fields shared by "settings" and "erode"; returns whether any was given.
bool parse_physics_fields(JsonFields& f, TalusSettings& t) {
    bool any = false;
    if (f.has("relocation_radius")) {
        t.parameters.relocation_radius = f.non_negative("relocation_radius", 0.0);
        any = true;
    }
    if (f.has("damping")) {
        t.parameters.damping = f.in_range("damping", 0.5, 0.01, 1.0);
        any = true;
    }
    if (f.has("settle_margin")) {
        t.parameters.settle_margin =
            f.in_range("settle_margin", t.parameters.settle_margin, 0.0, kMaxSettleMargin);
        any = true;
    }
    if (f.has("rest_tolerance")) {
        t.parameters.rest_tolerance = f.in_range("rest_tolerance", 1e-4, 0.0, 1.0);
        any = true;
    }
    if (f.has("rule")) {
        t.parameters.rule = f.choice("rule", "face", {"edge", "face"}) == "edge" ? SlopeRule::Edge
                                                                                 : SlopeRule::Face;
        any = true;
    }
    if (f.has("schedule")) {
        t.schedule = f.choice("schedule", "sequential", {"sequential", "jacobi"}) == "sequential"
                         ? Schedule::Sequential
                         : Schedule::Jacobi;
        any = true;
    }
    if (f.has("threads")) {
        t.threads = static_cast<int>(f.integer("threads", 1, 1, 64));
        any = true;
    }
    if (f.has("randomness")) {
        t.randomness = f.in_range("randomness", 0.0, 0.0, 0.99);
        any = true;
    }
    if (f.has("seed")) {
        t.seed = static_cast<std::uint64_t>(f.integer("seed", 1, 0, INT64_MAX));
        any = true;
    }
    if (f.has("quiet_iterations")) {
        t.quiet_iterations = static_cast<int>(f.integer("quiet_iterations", 3, 1, 255));
        any = true;
    }
    return any;
}

ScriptOperation parse_operation(const std::string& op, JsonFields& f, const nlohmann::json& object,
                                const std::filesystem::path& base_dir,
                                const std::vector<ScriptExtension>& extensions,
                                const TalusSettings& physics) {
    if (op == "stamp") {
        StampOp s;
        s.tool = parse_tool(f, base_dir);
        s.at = f.point("at");
        s.angle = f.number("angle", 0.0);
        parse_depth(f, s.depth_mode, s.depth);
        f.reject_unknown();
        return s;
    }
    if (op == "stroke") {
        StrokeOp s;
        s.tool = parse_tool(f, base_dir);
        s.path = f.points("path", 1);
        s.settings.spacing = f.positive("spacing", 0.25 * s.tool->radius());
        check_placement_count(f, path_length(s.path), s.settings.spacing);
        if (f.boolean("curve", false)) s.path = catmull_rom(s.path, s.settings.spacing / 4.0);
        parse_depth(f, s.settings.depth_mode, s.settings.depth);
        s.settings.follow_path = f.boolean("follow_path", true);
        s.settings.angle = f.number("angle", 0.0);
        if (f.boolean("erode", false)) {
            s.erode_iterations = static_cast<int>(f.integer("erode_iterations", 4, 1, 100000));
        } else if (f.has("erode_iterations")) {
            f.fail("'erode_iterations' needs \"erode\": true");
        }
        f.reject_unknown();
        return s;
    }
    if (op == "pour" || op == "remove") {
        PourOp p;
        p.remove = op == "remove";
        // Up to a kMaxHeight-deep pile over the largest terrain.
        p.volume = f.in_range("volume", 0.0, 0.0, kMaxHeight * kMaxHeight * kMaxHeight);
        if (!f.has("volume")) f.fail("missing required field 'volume'");
        p.settings.radius = f.positive("radius", p.settings.radius);
        p.settings.falloff = parse_falloff(f, "smooth");
        p.settings.refine_spacing = f.non_negative("refine_spacing", 0.0);
        p.points = parse_points(f, 0.5 * p.settings.radius);
        f.reject_unknown();
        return p;
    }
    if (op == "brush") {
        BrushOp b;
        const std::string kind =
            f.choice("kind", "raise", {"raise", "lower", "smooth", "flatten", "weather", "paint"});
        b.settings.kind = kind == "raise"     ? BrushKind::Raise
                          : kind == "lower"   ? BrushKind::Lower
                          : kind == "smooth"  ? BrushKind::Smooth
                          : kind == "flatten" ? BrushKind::Flatten
                          : kind == "weather" ? BrushKind::Weather
                                              : BrushKind::PaintMaterial;
        b.settings.radius = f.positive("radius", b.settings.radius);
        const bool fraction = b.settings.kind == BrushKind::Smooth ||
                              b.settings.kind == BrushKind::Flatten ||
                              b.settings.kind == BrushKind::Weather;
        b.settings.strength = fraction
                                  ? f.in_range("strength", 0.5, 0.0, 1.0)
                                  : f.in_range("strength", b.settings.strength, 0.0, kMaxHeight);
        b.settings.falloff = parse_falloff(f, "smooth");
        b.settings.refine_spacing = f.non_negative("refine_spacing", 0.0);
        // Fields another kind of brush reads would be ignored here: an error, as unknown ones.
        if (f.has("material") && b.settings.kind != BrushKind::PaintMaterial)
            f.fail_field("material", "applies to the paint brush, not to " + kind);
        if (f.has("height") && b.settings.kind != BrushKind::Flatten)
            f.fail_field("height", "applies to the flatten brush, not to " + kind);
        if (f.has("strength") && b.settings.kind == BrushKind::PaintMaterial)
            f.fail_field("strength", "does not apply to the paint brush");
        if (f.has("moisture") && b.settings.kind != BrushKind::PaintMaterial)
            f.fail_field("moisture", "applies to the paint brush, not to " + kind);
        if (f.has("moisture"))
            b.moisture = static_cast<float>(f.in_range("moisture", 0.0, 0.0, 1.0));
        b.settings.material = static_cast<std::uint16_t>(f.integer("material", 0, 0, 65535));
        if (f.has("height")) b.settings.flatten_to = height_field(f, "height", 0.0);
        b.points = parse_points(f, 0.25 * b.settings.radius);
        f.reject_unknown();
        return b;
    }
    if (op == "erode") {
        ErodeOp e;
        if (f.has("iterations") == f.boolean("until_rest", false)) {
            f.fail("give either 'iterations' or \"until_rest\": true");
        }
        e.until_rest = f.boolean("until_rest", false);
        if (!e.until_rest && f.has("max_iterations"))
            f.fail_field("max_iterations", "applies with \"until_rest\": true; give iterations");
        e.iterations = static_cast<int>(f.integer("iterations", 0, 1, 100'000'000));
        e.max_iterations = static_cast<int>(f.integer("max_iterations", 100000, 1, 100'000'000));
        e.project = f.boolean("project", false);
        if (!e.project && f.has("fit_bends"))
            f.fail_field("fit_bends", "applies with \"project\": true");
        e.fit_bends = static_cast<int>(f.integer("fit_bends", 0, 0, 8));
        TalusSettings t = physics;
        if (parse_physics_fields(f, t)) e.settings = t;
        if (e.project && !f.has("settle_margin")) {
            t.parameters.settle_margin = kSettleMarginAfterProjection;
            e.settings = t;
        }
        f.reject_unknown();
        return e;
    }
    if (op == "save") {
        const std::string path = f.text("path", "");
        if (path.empty()) f.fail("missing required field 'path'");
        f.reject_unknown();
        return SaveOp{base_dir / path};
    }
    if (op == "water") return parse_water_op(f, WaterOpKind::Water);
    if (op == "rain") return parse_water_op(f, WaterOpKind::Rain);
    if (op == "flow") return parse_water_op(f, WaterOpKind::Flow);
    if (op == "dry") return parse_dry_op(f);
    if (op == "weather") return parse_weather_op(f);
    if (op == "simplify") {
        SimplifyOp s;
        if (f.has("tolerance")) s.tolerance = f.positive("tolerance", 0.0);
        f.reject_unknown();
        return s;
    }
    for (const ScriptExtension& ext : extensions) {
        if (std::optional<CustomOp> custom = ext(op, object, f.context()))
            return std::move(*custom);
    }
    f.fail_field("op", "names an unknown operation '" + op + "'");
}

bool step_uses_physics(const ScriptStep& step) {
    if (std::holds_alternative<ErodeOp>(step.operation)) return true;
    const auto* stroke = std::get_if<StrokeOp>(&step.operation);
    return stroke != nullptr && stroke->erode_iterations > 0;
}

}  // namespace

Script parse_script(std::string_view text, const std::string& name,
                    const std::filesystem::path& base_dir,
                    const std::vector<ScriptExtension>& extensions) {
    const nlohmann::json document = parse_json_document(text, name);
    const std::vector<std::size_t> lines = operation_start_lines(text);

    Script script;
    script.name = name;
    const nlohmann::json* operations = &document;
    if (document.is_object()) {
        JsonFields top(document, name);
        top.integer("version", 1, 1, 1);
        if (const nlohmann::json* settings = top.get("settings")) {
            JsonFields s(*settings, name + ": settings");
            if (s.has("simplify_tolerance"))
                script.simplify_tolerance = s.positive("simplify_tolerance", 0.0);
            if (s.has("keep_generations")) {
                script.keep_generations =
                    static_cast<Generation>(s.integer("keep_generations", 64, 1, 1'000'000));
            }
            if (s.has("simplify")) script.simplify = s.boolean("simplify", true);
            parse_physics_fields(s, script.physics);
            s.reject_unknown();
        }
        if (const nlohmann::json* terrain = top.get("terrain")) {
            JsonFields t(*terrain, name + ": terrain");
            ScriptTerrain st;
            if (t.has("size")) {
                st.size = t.point("size");
                if (!(st.size.x > 0.0 && st.size.y > 0.0)) t.fail_field("size", "must be positive");
            }
            st.points = static_cast<std::size_t>(t.integer("points", 0, 0, 50'000'000));
            st.seed = static_cast<std::uint64_t>(t.integer("seed", 1, 0, INT64_MAX));
            st.height = height_field(t, "height", 0.0);
            if (t.has("sand_depth")) st.sand_depth = t.in_range("sand_depth", 0.0, 0.0, kMaxHeight);
            t.reject_unknown();
            script.terrain = st;
        }
        operations = &top.required("operations");
        top.reject_unknown();
    }
    if (!operations->is_array()) {
        throw JsonInputError(
            name + ": a script is an array of operations or an object with \"operations\"");
    }
    for (std::size_t k = 0; k < operations->size(); ++k) {
        const nlohmann::json& object = (*operations)[k];
        const std::size_t line = k < lines.size() ? lines[k] : 0;
        std::string context =
            name + ":" + std::to_string(line) + ": operation " + std::to_string(k + 1);
        if (!object.is_object()) throw JsonInputError(context + ": must be a JSON object");
        const auto op_it = object.find("op");
        if (op_it == object.end() || !op_it->is_string()) {
            throw JsonInputError(context + ": missing the string field 'op'");
        }
        const std::string op = op_it->get<std::string>();
        context += " (" + op + ")";
        JsonFields f(object, context);
        f.get("op");
        ScriptStep step{parse_operation(op, f, object, base_dir, extensions, script.physics), op,
                        line};
        if (step_uses_physics(step)) script.uses_physics = true;
        script.steps.push_back(std::move(step));
    }
    return script;
}

namespace {

nlohmann::json stamp_json(const StampReport& r) {
    nlohmann::json j = {{"stamps_applied", r.applied ? 1 : 0},
                        {"displaced_volume", r.displaced_volume},
                        {"deposited_volume", r.deposited_volume},
                        {"undeposited_volume", r.undeposited_volume},
                        {"retriangulation_volume", r.retriangulation_volume},
                        {"volume_change", r.volume_change},
                        {"vertices_inserted", r.vertices_inserted},
                        {"vertices_removed", r.vertices_removed},
                        {"triangles_touched", r.triangles_touched},
                        {"constraints_released", r.constraints_released},
                        {"edges_fenced", r.edges_fenced},
                        {"enforce_ms", r.enforce_ms},
                        {"simplify_ms", r.simplify_ms},
                        {"extrude_ms", r.extrude_ms}};
    if (const std::optional<std::string> w = lost_extrusion_warning(r)) j["warning"] = *w;
    return j;
}

/// A stamp or stroke that changed nothing (touched no triangle) says so: the artist asked for
/// a change.
void warn_if_nothing_stamped(nlohmann::json& j, const StampReport& total) {
    if (total.triangles_touched > 0 || j.contains("warning")) return;
    j["warning"] =
        "no stamp changed the terrain: the tool misses it, presses no deeper than its surface, "
        "or the terrain already holds its imprint";
}

/// About how many stamps a stroke places: one per spacing along its path (the tool's own limit
/// when that is shorter), and its start. Only progress reports use it.
double expected_stamp_count(const StrokeOp& op) {
    return path_length(op.path) / std::min(op.settings.spacing, op.tool->max_stroke_spacing()) +
           1.0;
}

/// A pour or removal that moved less than asked says how much and why.
void warn_if_short(nlohmann::json& j, bool remove, double asked, double moved) {
    if (const std::optional<std::string> w = short_pour_warning(remove, asked, moved))
        j["warning"] = *w;
}

}  // namespace

ScriptRunner::ScriptRunner(const Script& script, Tin& tin, SculptContext& context,
                           bool with_physics, const RelaxationSolverFactory& make_solver,
                           const Session* carried)
    : tin_(tin),
      context_(context),
      // A scene from the editor erodes with the materials it was sculpted with.
      materials_(carried != nullptr ? materials_or_presets(carried->metadata_json)
                                    : MaterialTable::presets()) {
    if (carried != nullptr) {
        carried_.metadata_json = carried->metadata_json;
        carried_.unknown_chunks = carried->unknown_chunks;
    }
    if (script.simplify_tolerance) context.settings.simplify.tolerance = *script.simplify_tolerance;
    if (script.keep_generations) context.settings.keep_generations = *script.keep_generations;
    if (script.simplify) context.settings.simplify_after_edit = *script.simplify;
    // The physics follows the TIN from the start, so it sees every change the script makes.
    if (script.uses_physics || with_physics) {
        solver_ = make_solver ? make_solver(tin, script.physics, materials_)
                              : std::make_unique<SandPhysics>(tin, materials_, script.physics);
    }
    // The terrain the script starts from (a loaded session, an imported elevation model) was
    // never relaxed by this physics: all of it is a candidate, or an `erode` would find nothing
    // active and report rest on walls far steeper than repose. Vertices already at rest leave
    // the active set after a few quiet iterations.
    if (solver_) solver_->activate_all();
}

ScriptRunner::~ScriptRunner() = default;

nlohmann::json ScriptRunner::run(const ScriptStep& step, const ProgressCallback& progress) {
    if (!solver_ && step_uses_physics(step)) {
        throw std::logic_error("ScriptRunner: step '" + step.op_name +
                               "' needs the physics, which this runner was created without");
    }
    erosion_drift_ = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    // Read only while this step runs, and cleared however it ends (a throwing step must not
    // leave a pointer to the caller's callback behind).
    struct StepProgress {
        const ProgressCallback*& slot;
        ~StepProgress() { slot = nullptr; }
    } clear_after{step_progress_};
    step_progress_ = progress ? &progress : nullptr;
    nlohmann::json r =
        std::visit([&](const auto& op) -> nlohmann::json { return run_op(op); }, step.operation);
    r["op"] = step.op_name;
    r["line"] = step.line;
    r["ms"] = elapsed_ms(t0);
    return r;
}

PhysicsStepReport ScriptRunner::relax(int iterations, bool until_rest) {
    // What float relaxation (the GPU) added or lost by rounding, m³. Every height it writes
    // goes through the TIN's volume ledger, so reading the ledger around each physics call
    // measures it without a pass over the terrain (a stroke erodes after every stamp).
    const double ledger = tin_.volume_ledger();
    PhysicsStepReport r = until_rest ? solver_->run_to_rest(iterations, &eroded_)
                                     : solver_->step(iterations, &eroded_);
    if (!solver_->conserves_volume_exactly()) erosion_drift_ += tin_.volume_ledger() - ledger;
    return r;
}

PhysicsStepReport ScriptRunner::erode(int iterations, bool until_rest) {
    // Relaxation, then the simplification of what it touched. Both conserve volume (the
    // relaxation to its arithmetic's rounding).
    SculptContext& context = context_;
    eroded_.clear();
    PhysicsStepReport r = relax(iterations, until_rest);
    context.simplifier.enqueue(eroded_);
    if (!context.settings.simplify_after_edit) return r;
    const SimplifyReport simplified = context.simplifier.run(tin_, context.settings.simplify);
    if (until_rest && r.at_rest && simplified.removed > 0) {
        // A removal re-triangulates its hole and shifts the hole's heights to keep the
        // volume, so the edges it leaves may be up to ~2 d_m steeper over their length:
        // on the short edges of a refined slope (r_S), several times the angle of repose
        // (measured: 2.5 on a groove at r_S = 1 cm). "Until rest" means the terrain the
        // step leaves is at rest, so those settle now; what that moves is queued for the
        // next edit's simplification.
        eroded_.clear();
        const PhysicsStepReport settle = relax(iterations, true);
        context.simplifier.enqueue(eroded_);
        r.accumulate(settle);
    }
    return r;
}

void ScriptRunner::report_points_done(std::size_t done, std::size_t total) const {
    if (step_progress_)
        (*step_progress_)({static_cast<double>(done) / static_cast<double>(total), {}});
}

nlohmann::json ScriptRunner::run_op(const StampOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    ToolPlacement at{op.at, op.angle, op.depth};
    if (op.depth_mode == DepthMode::Relative) {
        const Rect d = tin.domain();
        const Vec2 c{std::clamp(op.at.x, d.min.x, d.max.x), std::clamp(op.at.y, d.min.y, d.max.y)};
        at.bottom = tin.height_at(c, &context.hint).value_or(0.0) - op.depth;
    }
    const StampReport report = stamp(tin, *op.tool, at, context);
    nlohmann::json j = stamp_json(report);
    warn_if_nothing_stamped(j, report);
    return j;
}

nlohmann::json ScriptRunner::run_op(const StrokeOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    std::vector<StampReport> per;
    PhysicsStepReport physics_total;
    std::function<void(const StampReport&)> after_stamp;
    // Progress counts stamps against the count the path's length and spacing promise.
    const double expected_stamps = step_progress_ ? expected_stamp_count(op) : 0.0;
    std::size_t stamped = 0;
    if (op.erode_iterations > 0 || step_progress_) {
        after_stamp = [&](const StampReport&) {
            if (op.erode_iterations > 0)
                physics_total.accumulate(erode(op.erode_iterations, false));
            if (step_progress_)
                (*step_progress_)({std::min(++stamped / expected_stamps, 0.99), {}});
        };
    }
    const StampReport total =
        apply_stroke(tin, *op.tool, op.path, op.settings, context, &per, after_stamp);
    nlohmann::json j = stamp_json(total);
    j["stamps_applied"] = per.size();
    warn_if_nothing_stamped(j, total);
    if (op.erode_iterations > 0) {
        j["erosion_iterations"] = physics_total.iterations;
        j["erosion_ms"] = physics_total.ms;
        j["volume_change"] = j["volume_change"].get<double>() + erosion_drift_;
    }
    return j;
}

nlohmann::json ScriptRunner::run_op(const ErodeOp& op) {
    const TalusSettings saved = solver_->settings();
    if (op.settings) solver_->settings() = *op.settings;
    nlohmann::json projection;
    double projection_drift = 0.0;
    if (op.project) {
        const ProjectionSettleReport p =
            op.fit_bends > 0 ? settle_fitted_to_kinks(tin_, materials_, op.fit_bends)
                             : settle_by_projection(tin_, materials_);
        projection = {{"iterations", p.iterations},         {"converged", p.converged},
                      {"steep_faces", p.steep_faces},       {"rounds", p.rounds},
                      {"free_vertices", p.free_vertices},   {"moved_vertices", p.moved_vertices},
                      {"steepest_ratio", p.steepest_ratio}, {"fitted_vertices", p.fitted_vertices}};
        // Each solver follows the TIN's changes: the vertices the projection moved are active.
        projection_drift = p.volume_change;
    }
    const PhysicsStepReport pr =
        op.until_rest ? erode(op.max_iterations, true) : erode(op.iterations, false);
    solver_->settings() = saved;
    nlohmann::json j = {{"iterations", pr.iterations},
                        {"vertex_updates", pr.vertex_updates},
                        {"refined", pr.refined},
                        {"volume_moved", pr.volume_moved},
                        {"at_rest", pr.at_rest},
                        {"erosion_ms", pr.ms},
                        {"volume_change", erosion_drift_ + projection_drift}};
    if (op.project) j["projection"] = projection;
    return j;
}

nlohmann::json ScriptRunner::run_op(const PourOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    const double each = op.volume / static_cast<double>(std::max<std::size_t>(op.points.size(), 1));
    double moved = 0.0;
    for (std::size_t k = 0; k < op.points.size(); ++k) {
        const Vec2 p = op.points[k];
        const PourReport pr = op.remove ? remove_sand(tin, p, each, op.settings, context)
                                        : pour_sand(tin, p, each, op.settings, context);
        moved += pr.volume;
        report_points_done(k + 1, op.points.size());
    }
    if (context.settings.simplify_after_edit)
        context.simplifier.run(tin, context.settings.simplify);
    nlohmann::json j = {{"volume", moved}, {"points", op.points.size()}, {"volume_change", moved}};
    warn_if_short(j, op.remove, op.volume, moved);
    return j;
}

nlohmann::json ScriptRunner::run_op(const BrushOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    BrushSettings settings = op.settings;
    if (settings.kind == BrushKind::PaintMaterial) {
        if (settings.material >= materials_.size()) {
            std::string names;
            for (std::size_t m = 0; m < materials_.size(); ++m)
                names += (m ? ", " : "") + std::to_string(m) + " " + materials_.all()[m].name;
            throw std::invalid_argument("material " + std::to_string(settings.material) +
                                        ": the scene has " + std::to_string(materials_.size()) +
                                        " materials (" + names + ")");
        }
        settings.moisture = op.moisture.value_or(materials_.at(settings.material).default_moisture);
    }
    std::size_t changed = 0;
    double dv = 0.0;
    for (std::size_t k = 0; k < op.points.size(); ++k) {
        const BrushReport br = apply_brush(tin, op.points[k], settings, context);
        changed += br.vertices_changed;
        dv += br.volume_change;
        report_points_done(k + 1, op.points.size());
    }
    return {{"dabs", op.points.size()}, {"vertices_changed", changed}, {"volume_change", dv}};
}

nlohmann::json ScriptRunner::run_op(const SimplifyOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    SimplifySettings s = context.settings.simplify;
    if (op.tolerance) s.tolerance = *op.tolerance;
    // An explicit simplify tests every vertex, not only the queue.
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i) {
        if (tin.is_alive(VertexId{i})) context.simplifier.enqueue(VertexId{i});
    }
    const SimplifyReport sr = context.simplifier.run(tin, s);
    // Removals shift their neighbours to conserve volume (VolumePolicy::Conserve);
    // "retriangulation_volume" is what they changed before that compensation.
    return {{"tested", sr.tested},
            {"removed", sr.removed},
            {"retriangulation_volume", sr.volume_change},
            {"max_retriangulation_volume", sr.max_volume_change},
            {"volume_change", s.volume_policy == VolumePolicy::Conserve ? 0.0 : sr.volume_change}};
}

nlohmann::json ScriptRunner::run_op(const SaveOp& op) {
    Tin& tin = tin_;
    SculptContext& context = context_;
    Session session = carried_;
    session.terrain = tin.snapshot();
    session.next_generation = context.peek_generation();
    save_session(op.path, session);
    return {{"file", op.path.string()}, {"volume_change", 0.0}};
}

nlohmann::json ScriptRunner::run_op(const WaterOp& op) {
    std::vector<VertexId> reached;
    nlohmann::json report = run_water_op(op, tin_, &reached);
    // The ground the water left dry is simplified as after any edit: the detail added under
    // it goes where it is dry and planar again (the simplifier leaves wet ground alone).
    SculptContext& context = context_;
    if (op.detail > 0.0 && context.settings.simplify_after_edit) {
        context.simplifier.enqueue(reached);
        report["simplified_vertices"] =
            context.simplifier.run(tin_, context.settings.simplify).removed;
    }
    return report;
}

// Moisture changes reach the physics through the TIN's vertex feed, as the water's do: its
// next sync recomputes the angle of repose of every vertex whose moisture changed.
nlohmann::json ScriptRunner::run_op(const DryOp& op) {
    return run_dry_op(op, tin_);
}

nlohmann::json ScriptRunner::run_op(const WeatherOp& op) {
    return run_weather_op(op, tin_);
}

nlohmann::json ScriptRunner::run_op(const CustomOp& op) {
    return op.run(tin_, context_);
}

Tin make_script_terrain(const ScriptTerrain& t, TinOptions options) {
    const Rect domain = Rect::from_size(t.size.x, t.size.y);
    Tin tin = t.points == 0
                  ? Tin::flat_rectangle(domain, t.height, options)
                  : Tin::random_points(
                        domain, t.points, t.seed, [&t](Vec2) { return t.height; }, options);
    if (t.sand_depth) lay_flat_bedrock(tin, t.height - *t.sand_depth);
    return tin;
}

nlohmann::json run_script(const Script& script, Tin& tin, SculptContext& context,
                          const RelaxationSolverFactory& make_solver, const Session* carried,
                          const ProgressCallback& progress) {
    ScriptRunner runner(script, tin, context, false, make_solver, carried);
    nlohmann::json reports = nlohmann::json::array();
    const auto where = [&](std::size_t line) {
        return script.name.empty() ? "line " + std::to_string(line)
                                   : script.name + ":" + std::to_string(line);
    };
    const std::size_t n = script.steps.size();
    for (std::size_t i = 0; i < n; ++i) {
        const ScriptStep& step = script.steps[i];
        ProgressCallback step_progress;
        const std::string stage = progress ? "operation " + std::to_string(i + 1) + " of " +
                                                 std::to_string(n) + " (" + step.op_name + ")"
                                           : std::string();
        if (progress) {
            progress({static_cast<double>(i) / static_cast<double>(n), stage});
            step_progress = [&](const Progress& p) {
                progress({(static_cast<double>(i) + p.fraction) / static_cast<double>(n), stage});
            };
        }
        try {
            nlohmann::json report = runner.run(step, step_progress);
            // A warning names its operation as an error would, so the artist finds it.
            if (const auto w = report.find("warning"); w != report.end() && w->is_string()) {
                *w = where(step.line) + ": operation " + std::to_string(i + 1) + " (" +
                     step.op_name + "): " + w->get<std::string>();
            }
            reports.push_back(std::move(report));
        } catch (const std::invalid_argument& e) {
            // Input that only the terrain shows to be bad: named by its line, like a parse
            // error.
            throw std::invalid_argument(where(step.line) + ": operation " + std::to_string(i + 1) +
                                        " (" + step.op_name + "): " + e.what());
        }
    }
    if (progress) progress({1.0, "done"});
    return reports;
}

}  // namespace sandtin
