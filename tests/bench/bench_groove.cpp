#include "bench_groove.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "physics/sand_physics.hpp"
#include "tin/tin.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::bench {

namespace {

struct GrooveRun {
    double total_ms = 0.0;
    double enforce_ms = 0.0;
    double simplify_ms = 0.0;
    double per_stamp_median_ms = 0.0;
    double per_stamp_p90_ms = 0.0;
    /// Vertices a stamp removes (the fresh sand it digs out, cleared in bulk or simplified):
    /// at 10^6 points hundreds per stamp, the part of a stamp's work that grows with density.
    double removed_per_stamp_median = 0.0;
    double cleared_per_stamp_median = 0.0;
    /// With erosion between stamps (kErosionIterations after each, then the simplification of
    /// what it moved, as a script's stroke with "erode": true does); 0 without.
    double erosion_ms = 0.0;
    double erosion_per_stamp_median_ms = 0.0;
    /// The slowest stamp's erosion: a one-off cost (a pool that grows) is a hitch the artist
    /// sees, which the median hides.
    double erosion_per_stamp_max_ms = 0.0;
    /// Its two parts per stamp (medians): the relaxation (SandPhysics::step, with its
    /// bookkeeping of the stamp's changes) and the simplification of what it moved.
    double erosion_relax_per_stamp_median_ms = 0.0;
    double erosion_simplify_per_stamp_median_ms = 0.0;
    double erosion_relax_ms = 0.0;  ///< the relaxation's share of erosion_ms
    std::size_t erosion_vertex_updates = 0;
    /// Over the same iterations, the heights that changed (PhysicsStepReport::changed).
    std::size_t erosion_heights_changed = 0;
    /// Erosion to rest after the stroke (Erosion::ToRestAfter): the relaxation and the
    /// simplification of what it moved.
    double rest_ms = 0.0;
    int rest_iterations = 0;
    std::size_t rest_vertex_updates = 0;
    bool at_rest = false;
    std::size_t stamps = 0;
    std::size_t vertices_before = 0;
    std::size_t vertices_after = 0;
    std::size_t triangles_touched = 0;
    std::size_t constrained_edges_after = 0;
    bool valid = false;
};

constexpr double kBottom = -0.1;   ///< the tool's lowest point (m)
constexpr double kSpacing = 0.01;  ///< distance between stamps along the stroke (m)
/// Relaxation iterations after each stamp when the groove erodes (a script stroke's default).
constexpr int kErosionIterations = 4;
/// Iterations allowed for the groove to come to rest (it takes about 1 500 at 10^4 points).
constexpr int kMaxRestIterations = 200000;

enum class Erosion {
    None,
    BetweenStamps,  ///< kErosionIterations after every stamp
    ToRestAfter,    ///< none during the stroke, then until the sand rests
};

/// The seeds' tool: a circle of radius 0.04 with 12 control points.
ToolSpec seeds_circle() {
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = 0.04;
    spec.control_points = 12;
    return spec;
}

/// A flat TIN of n random points on a square of side `side` metres (the unit square unless
/// asked); the tool (the seeds' circle unless another is asked for) with its bottom at -0.1; a
/// stroke along the diagonal from (0.5 - L/2)(side, side) to (0.5 + L/2)(side, side), where L is
/// the trace length as a fraction of the diagonal. Stamps are 1 cm apart: for the circle r/4, so
/// consecutive footprints overlap by 7/8 and the walls are smooth to 0.3 mm. With erosion, dry sand
/// relaxes with the physics' defaults (the editor's) for kErosionIterations after every stamp, or
/// after the stroke until it rests; what it moved is then simplified. Its time is kept apart from
/// the stamps' enforcement and simplification.
GrooveRun run_groove(const Tool& tool, std::size_t n, double trace, bool validate,
                     bool clear_before_imprint = true, Erosion erosion = Erosion::None,
                     TalusSettings physics_settings = {}, double side = 1.0,
                     bool fence_coarse_edges = true) {
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::random_points(Rect::from_size(side, side), n, 2009, {}, options);
    SculptContext context(tin.domain());
    context.settings.clear_before_imprint = clear_before_imprint;
    context.settings.fence_coarse_edges = fence_coarse_edges;
    std::unique_ptr<SandPhysics> physics;
    if (erosion != Erosion::None) {
        physics = std::make_unique<SandPhysics>(tin, MaterialTable::presets(), physics_settings);
    }
    StrokeSettings settings;
    settings.spacing = kSpacing;
    settings.depth_mode = DepthMode::Absolute;
    settings.depth = kBottom;
    const double low = (0.5 - 0.5 * trace) * side;
    const double high = (0.5 + 0.5 * trace) * side;
    const std::vector<Vec2> path = {{low, low}, {high, high}};

    GrooveRun run;
    run.vertices_before = tin.vertex_count();
    std::vector<StampReport> stamps;
    std::vector<double> erosion_ms, relax_ms, simplify_ms;
    std::vector<VertexId> moved;
    std::function<void(const StampReport&)> after_stamp;
    if (erosion == Erosion::BetweenStamps) {
        after_stamp = [&](const StampReport&) {
            Stopwatch e;
            moved.clear();
            const PhysicsStepReport r = physics->step(kErosionIterations, &moved);
            run.erosion_vertex_updates += r.vertex_updates;
            run.erosion_heights_changed += r.changed;
            relax_ms.push_back(e.ms());
            Stopwatch simplify;
            context.simplifier.enqueue(moved);
            context.simplifier.run(tin, context.settings.simplify);
            simplify_ms.push_back(simplify.ms());
            erosion_ms.push_back(e.ms());
        };
    }
    Stopwatch w;
    const StampReport total =
        apply_stroke(tin, tool, path, settings, context, &stamps, after_stamp);
    run.total_ms = w.ms();
    if (erosion == Erosion::ToRestAfter) {
        Stopwatch rest;
        moved.clear();
        const PhysicsStepReport r = physics->run_to_rest(kMaxRestIterations, &moved);
        context.simplifier.enqueue(moved);
        context.simplifier.run(tin, context.settings.simplify);
        run.rest_ms = rest.ms();
        run.rest_iterations = r.iterations;
        run.rest_vertex_updates = r.vertex_updates;
        run.at_rest = r.at_rest;
    }
    for (double ms : erosion_ms)
        run.erosion_ms += ms;
    run.erosion_per_stamp_median_ms = median(erosion_ms);
    run.erosion_per_stamp_max_ms =
        erosion_ms.empty() ? 0.0 : *std::max_element(erosion_ms.begin(), erosion_ms.end());
    run.erosion_relax_per_stamp_median_ms = median(relax_ms);
    for (double ms : relax_ms)
        run.erosion_relax_ms += ms;
    run.erosion_simplify_per_stamp_median_ms = median(simplify_ms);
    run.enforce_ms = total.enforce_ms;
    run.simplify_ms = total.simplify_ms;
    std::vector<double> per;
    for (const StampReport& s : stamps)
        per.push_back(s.enforce_ms + s.simplify_ms + s.extrude_ms);
    run.per_stamp_median_ms = median(per);
    std::vector<double> removed;
    std::vector<double> cleared;
    for (const StampReport& s : stamps) {
        removed.push_back(static_cast<double>(s.vertices_removed));
        cleared.push_back(static_cast<double>(s.cleared.removed));
    }
    run.removed_per_stamp_median = median(removed);
    run.cleared_per_stamp_median = median(cleared);
    std::sort(per.begin(), per.end());
    run.per_stamp_p90_ms = per.empty() ? 0.0 : per[per.size() * 9 / 10];
    run.stamps = stamps.size();
    run.vertices_after = tin.vertex_count();
    run.triangles_touched = total.triangles_touched;
    run.constrained_edges_after = tin.constrained_edge_count();
    run.valid = !validate || tin.check_valid().ok();
    return run;
}

/// The stroke's whole time, and with the rest after it (Erosion::ToRestAfter).
double stroke_ms(const GrooveRun& r) {
    return r.total_ms;
}
double stroke_and_rest_ms(const GrooveRun& r) {
    return r.total_ms + r.rest_ms;
}

/// The run with the median `time` (the upper middle of an even count).
GrooveRun median_by(std::vector<GrooveRun> runs, double (*time)(const GrooveRun&)) {
    std::sort(runs.begin(), runs.end(),
              [&](const GrooveRun& a, const GrooveRun& b) { return time(a) < time(b); });
    return runs[runs.size() / 2];
}

/// The run with the median whole-stroke time.
GrooveRun median_by_total(std::vector<GrooveRun> runs) {
    return median_by(std::move(runs), stroke_ms);
}

nlohmann::json to_json(const GrooveRun& r) {
    return {{"stamps", r.stamps},
            {"total_ms", r.total_ms},
            {"enforce_ms", r.enforce_ms},
            {"simplify_ms", r.simplify_ms},
            {"per_stamp_median_ms", r.per_stamp_median_ms},
            {"per_stamp_p90_ms", r.per_stamp_p90_ms},
            {"removed_per_stamp_median", r.removed_per_stamp_median},
            {"cleared_per_stamp_median", r.cleared_per_stamp_median},
            {"vertices_before", r.vertices_before},
            {"vertices_after", r.vertices_after},
            {"triangles_touched", r.triangles_touched},
            {"constrained_edges_after", r.constrained_edges_after},
            {"valid", r.valid}};
}

/// A groove with erosion: the same figures, and the relaxation's time apart from the stamps'.
nlohmann::json erosion_json(const GrooveRun& r) {
    nlohmann::json j = to_json(r);
    j["erosion_iterations_per_stamp"] = kErosionIterations;
    j["erosion_ms"] = r.erosion_ms;
    j["erosion_per_stamp_median_ms"] = r.erosion_per_stamp_median_ms;
    j["erosion_per_stamp_max_ms"] = r.erosion_per_stamp_max_ms;
    j["erosion_relax_per_stamp_median_ms"] = r.erosion_relax_per_stamp_median_ms;
    j["erosion_simplify_per_stamp_median_ms"] = r.erosion_simplify_per_stamp_median_ms;
    // What issue 41 asks of small active sets (>= 10⁷), over the relaxation's time.
    j["relax_vertex_updates_per_second"] =
        r.erosion_relax_ms > 0.0
            ? static_cast<double>(r.erosion_vertex_updates) / (r.erosion_relax_ms * 1e-3)
            : 0.0;
    j["erosion_vertex_updates"] = r.erosion_vertex_updates;
    // What the active set holds (issue 41 asks what makes small active sets slow): near 1, the
    // relaxation visits sand that moves; near 0, vertices counting quiet iterations down.
    // Receivers count too, so it may exceed 1.
    j["relax_heights_changed_per_update"] = r.erosion_vertex_updates > 0
                                                ? static_cast<double>(r.erosion_heights_changed) /
                                                      static_cast<double>(r.erosion_vertex_updates)
                                                : 0.0;
    return j;
}

/// The groove cut, then eroded to rest under `physics`: the run with the median whole time
/// (stroke and rest) of `reps`, valid when the first of them, the one validated, is.
GrooveRun median_to_rest(const Tool& tool, std::size_t n, int reps, const TalusSettings& physics) {
    std::vector<GrooveRun> runs;
    for (int r = 0; r < reps; ++r)
        runs.push_back(run_groove(tool, n, 0.8, r == 0, true, Erosion::ToRestAfter, physics));
    const bool valid = runs.front().valid;
    GrooveRun mid = median_by(std::move(runs), stroke_and_rest_ms);
    mid.valid = valid;
    return mid;
}

/// The groove cut, then eroded to rest (DESIGN.md §10: at 10^4 points, "incl. erosion to rest
/// <= 100 ms in all"): median of `reps` runs by the whole time, with the physics' defaults
/// (the face rule); the same under the edge rule at the same settle margin, side by side (the
/// target was set when the edge rule was the default: issue 41 asks it of the face rule, whose
/// visit costs about twice as much); and one run under the seeds' rule (the edge rule with no
/// settle margin) for comparison.
nlohmann::json to_rest_json(const Tool& tool, std::size_t n, int reps) {
    constexpr double kTargetMs = 100.0;  // at 10^4 points
    const TalusSettings defaults;
    TalusSettings edge = defaults;
    edge.parameters.rule = SlopeRule::Edge;
    const TalusSettings seeds = seeds_rule();
    const GrooveRun mid = median_to_rest(tool, n, reps, defaults);
    const GrooveRun edge_run = median_to_rest(tool, n, reps, edge);
    const GrooveRun seeds_run = run_groove(tool, n, 0.8, false, true, Erosion::ToRestAfter, seeds);
    auto summary = [](const GrooveRun& r, const TalusSettings& physics) {
        return nlohmann::json{
            {"rule", physics.parameters.rule == SlopeRule::Face ? "face" : "edge"},
            {"settle_margin", physics.parameters.settle_margin},
            {"stroke_ms", r.total_ms},
            {"rest_ms", r.rest_ms},
            {"total_ms", stroke_and_rest_ms(r)},
            {"iterations", r.rest_iterations},
            {"vertex_updates", r.rest_vertex_updates},
            {"at_rest", r.at_rest}};
    };
    nlohmann::json j = summary(mid, defaults);
    j["vertices_after"] = mid.vertices_after;
    j["valid"] = mid.valid && edge_run.valid;
    j["repetitions"] = reps;
    j["edge_rule"] = summary(edge_run, edge);
    j["edge_rule"]["repetitions"] = reps;
    j["seeds_rule"] = summary(seeds_run, seeds);
    if (n == 10000) {
        j["target_ms"] = kTargetMs;
        j["met"] = stroke_and_rest_ms(mid) <= kTargetMs;
        j["edge_rule"]["met"] = stroke_and_rest_ms(edge_run) <= kTargetMs;
    }
    return j;
}

/// Whether a stamp's cost follows the terrain's size or only the sand under the tool: a groove
/// of `n` points (on the unit square, per-stamp median `per_stamp_median_ms`) again with
/// n * side^2 points on a square of side `side` metres, so at the same density: the same sand
/// under every stamp, tool and stamp spacing unchanged. Equal per-stamp medians mean a stamp's
/// cost follows the density under the tool, not the terrain's size: the growth over `by_size`
/// is then the denser sand each stamp digs out (removed_per_stamp_median there), not a stamp
/// reaching beyond its footprint.
nlohmann::json same_density_json(const Tool& tool, std::size_t n, double per_stamp_median_ms,
                                 double side, int reps) {
    const auto points =
        static_cast<std::size_t>(std::llround(static_cast<double>(n) * side * side));
    std::vector<GrooveRun> runs;
    for (int r = 0; r < reps; ++r)
        runs.push_back(run_groove(tool, points, 0.8, r == 0, true, Erosion::None, {}, side));
    const bool valid = runs.front().valid;
    const GrooveRun mid = median_by_total(runs);
    return {{"unit_square", {{"points", n}, {"per_stamp_median_ms", per_stamp_median_ms}}},
            {"points", points},
            {"side_m", side},
            {"stamps", mid.stamps},
            {"per_stamp_median_ms", mid.per_stamp_median_ms},
            {"removed_per_stamp_median", mid.removed_per_stamp_median},
            {"repetitions", reps},
            {"valid", valid},
            {"per_stamp_ratio",
             per_stamp_median_ms > 0.0 ? mid.per_stamp_median_ms / per_stamp_median_ms : 0.0}};
}

}  // namespace

nlohmann::json bench_groove(const BenchConfig& config) {
    nlohmann::json j;
    j["bench"] = "groove";
    const ToolSpec spec = config.tool.empty() ? seeds_circle() : load_tool_asset(config.tool);
    const Tool tool = Tool::build(spec);
    j["tool"] = {{"name", spec.name},
                 {"bounding_radius", tool.shape().bounding_radius},
                 {"bottom", kBottom},
                 // A stroke keeps to the tool's own limit (Tool::max_stroke_spacing: the
                 // rake's 9 mm).
                 {"spacing", std::min(kSpacing, tool.max_stroke_spacing())}};
    if (config.tool.empty()) {
        j["tool"]["radius"] = spec.radius;
        j["tool"]["control_points"] = spec.control_points;
    } else {
        j["tool"]["asset"] = config.tool;
    }
    const std::vector<std::size_t> sizes = config.quick
                                               ? std::vector<std::size_t>{1000, 10000}
                                               : std::vector<std::size_t>{10000, 100000, 1000000};
    // Progress: a groove run costs about its terrain's build (its point count) and its ~80
    // stamps (taken here as 2·10⁴ points' worth); the weights shape the percentages only.
    auto runs_cost = [](double points, int runs) { return (points + 2e4) * runs; };
    const int trace_reps = config.quick ? 1 : 3;
    const int locality_reps = config.quick ? 1 : 3;
    const std::size_t trace_points = config.quick ? 1000 : 10000;
    double work = 0.0;
    for (std::size_t n : sizes) {
        const int reps = config.quick ? 1 : (n >= 1000000 ? 3 : 5);
        work += runs_cost(static_cast<double>(n), 3 * reps + 2);
        if (n <= 10000) work += runs_cost(static_cast<double>(n), (config.quick ? 1 : 3) + 1);
    }
    work += runs_cost(100.0 * static_cast<double>(sizes.front()), locality_reps);
    work += runs_cost(0.1 * static_cast<double>(sizes.back()), locality_reps);
    work += 8 * runs_cost(static_cast<double>(trace_points), trace_reps + 2);
    WeightedProgress progress(config.progress, work);

    nlohmann::json by_size = nlohmann::json::array();
    std::vector<double> medians;
    for (std::size_t n : sizes) {
        // Median over repetitions of the whole groove; the per-stamp figures are from the
        // repetition with the median total.
        // The same groove without the stamp's bulk clearing (SculptSettings::
        // clear_before_imprint), alternating with the default runs, for the ratio.
        // And without the fence against re-shaping coarse terrain (SculptSettings::
        // fence_coarse_edges), which finds nothing to fence in sand: what looking costs.
        std::vector<GrooveRun> runs;
        std::vector<GrooveRun> plain;
        std::vector<GrooveRun> unfenced;
        const int reps = config.quick ? 1 : (n >= 1000000 ? 3 : 5);
        for (int r = 0; r < reps; ++r) {
            progress.start("groove on " + std::to_string(n) + " points, run " +
                               std::to_string(r + 1) + " of " + std::to_string(reps),
                           runs_cost(static_cast<double>(n), 3));
            runs.push_back(run_groove(tool, n, 0.8, r == 0));
            plain.push_back(run_groove(tool, n, 0.8, false, false));
            unfenced.push_back(
                run_groove(tool, n, 0.8, false, true, Erosion::None, {}, 1.0, false));
        }
        const GrooveRun mid = median_by_total(runs);
        const GrooveRun plain_mid = median_by_total(plain);
        nlohmann::json row = to_json(mid);
        row["without_bulk_clearing"] = {
            {"per_stamp_median_ms", plain_mid.per_stamp_median_ms},
            {"total_ms", plain_mid.total_ms},
            {"vertices_after", plain_mid.vertices_after},
            {"per_stamp_ratio", mid.per_stamp_median_ms / plain_mid.per_stamp_median_ms}};
        const GrooveRun unfenced_mid = median_by_total(unfenced);
        row["without_fence"] = {
            {"per_stamp_median_ms", unfenced_mid.per_stamp_median_ms},
            {"total_ms", unfenced_mid.total_ms},
            {"vertices_after", unfenced_mid.vertices_after},
            {"per_stamp_ratio", mid.per_stamp_median_ms / unfenced_mid.per_stamp_median_ms}};
        // Once more with erosion after every stamp (one run: the relaxation's share is what
        // it adds, not a target).
        progress.start("groove on " + std::to_string(n) + " points with erosion",
                       runs_cost(static_cast<double>(n), 2));
        const GrooveRun eroded = run_groove(tool, n, 0.8, true, true, Erosion::BetweenStamps);
        row["with_erosion"] = erosion_json(eroded);
        // Eroded to rest after the stroke: cheap up to 10^4 points (the time to rest grows with
        // the vertices and the iterations an avalanche needs to cross them).
        if (n <= 10000) {
            progress.start("groove on " + std::to_string(n) + " points eroded to rest",
                           runs_cost(static_cast<double>(n), 2 * (config.quick ? 1 : 3) + 1));
            row["to_rest"] = to_rest_json(tool, n, config.quick ? 1 : 3);
        }
        row["points"] = n;
        row["repetitions"] = reps;
        row["valid"] = runs.front().valid;  // the first run is the validated one
        by_size.push_back(row);
        medians.push_back(mid.per_stamp_median_ms);
    }
    j["by_size"] = by_size;
    j["per_stamp_growth"] = medians.front() > 0.0 ? medians.back() / medians.front() : 0.0;
    // Locality: the smallest groove's density on a terrain 100 times larger, and the largest
    // groove's on one 10 times smaller.
    progress.start("locality: the same density on a terrain 100 times larger",
                   runs_cost(100.0 * static_cast<double>(sizes.front()), locality_reps));
    nlohmann::json larger =
        same_density_json(tool, sizes.front(), medians.front(), 10.0, locality_reps);
    progress.start("locality: the same density on a terrain 10 times smaller",
                   runs_cost(0.1 * static_cast<double>(sizes.back()), locality_reps));
    j["locality"] = {{"larger_terrain", std::move(larger)},
                     {"smaller_terrain", same_density_json(tool, sizes.back(), medians.back(),
                                                           std::sqrt(0.1), locality_reps)}};
    nlohmann::json by_trace = nlohmann::json::array();
    const std::size_t n = trace_points;
    for (int k = 1; k <= 8; ++k) {
        const double trace = 0.1 * k;
        progress.start("trace length " + std::to_string(k) + " of 8",
                       runs_cost(static_cast<double>(n), trace_reps + 2));
        std::vector<GrooveRun> runs;
        for (int r = 0; r < trace_reps; ++r)
            runs.push_back(run_groove(tool, n, trace, false));
        nlohmann::json row = to_json(median_by_total(runs));
        row["with_erosion"] =
            erosion_json(run_groove(tool, n, trace, false, true, Erosion::BetweenStamps));
        row["trace"] = trace;
        row["points"] = n;
        by_trace.push_back(row);
    }
    j["by_trace"] = by_trace;
    progress.done();
    return j;
}

}  // namespace sandtin::bench
