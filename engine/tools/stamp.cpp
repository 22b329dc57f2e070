#include "tools/stamp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "tools/detail/stamp_phases.hpp"
#include "tools/slivers.hpp"
#include "util/elapsed_ms.hpp"

namespace sandtin {

void StampReport::accumulate(const StampReport& o) {
    applied = applied || o.applied;
    generation = std::max(generation, o.generation);
    displaced_volume += o.displaced_volume;
    deposited_volume += o.deposited_volume;
    undeposited_volume += o.undeposited_volume;
    retriangulation_volume += o.retriangulation_volume;
    volume_change += o.volume_change;
    vertices_inserted += o.vertices_inserted;
    vertices_removed += o.vertices_removed;
    triangles_touched += o.triangles_touched;
    constraints_released += o.constraints_released;
    edges_fenced += o.edges_fenced;
    simplify.accumulate(o.simplify);
    cleared.candidates += o.cleared.candidates;
    cleared.removed += o.cleared.removed;
    cleared.patches += o.cleared.patches;
    cleared.refused += o.cleared.refused;
    enforce_ms += o.enforce_ms;
    simplify_ms += o.simplify_ms;
    extrude_ms += o.extrude_ms;
}

std::optional<std::string> lost_extrusion_warning(const StampReport& report) {
    const double lost = report.undeposited_volume;
    const double owed = report.deposited_volume + lost;
    if (!(std::abs(lost) > 0.01 * std::abs(owed))) return std::nullopt;
    char text[320];
    std::snprintf(text, sizeof text,
                  "extrusion had nowhere to put %.3g m³ of the %.3g m³ the tool pushed: the band "
                  "beside it, where the ridge goes, lies outside the terrain, so that sand left "
                  "the terrain (a tool smaller than the terrain, or extrusion off, keeps it)",
                  std::abs(lost), std::abs(owed));
    return std::string(text);
}

namespace {

std::string metres(double m) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g m", m);
    return std::string(text);
}

/// Throws unless the placement is finite and the tool's contours lie far enough apart on this
/// terrain. Points closer than the snap distance are one vertex: an inner contour that close to
/// the outer one would merge with the rim, and the stamp would dig nothing.
void require_stampable(const Tin& tin, const Tool& tool, const ToolPlacement& at) {
    if (!is_finite(at.centre) || !std::isfinite(at.angle) || !std::isfinite(at.bottom)) {
        throw std::invalid_argument("stamp: tool placement is not finite");
    }
    if (tool.shape().gap > 4.0 * tin.snap_distance()) return;
    const double k = 4.0 * tin.snap_distance() / tool.shape().gap;
    throw std::invalid_argument(
        "stamp: the tool is too small for this terrain: its contours are " +
        metres(tool.shape().gap) + " apart, within four snap distances (" +
        metres(tin.snap_distance()) +
        " on a terrain this size), so the inner one would merge with the rim and dig "
        "nothing; use a radius of at least " +
        metres(k * tool.radius()) + ", or a gap above " + metres(4.0 * tin.snap_distance()));
}

}  // namespace

// The steps as tools/stamp.hpp lists them; each phase is a function of
// tools/detail/stamp_phases.hpp, with the reasons for what it does.
StampReport stamp(Tin& tin, const Tool& tool, const ToolPlacement& at, SculptContext& context,
                  std::optional<Vec2> motion) {
    using namespace detail;
    StampReport report;
    const auto t0 = std::chrono::steady_clock::now();
    require_stampable(tin, tool, at);
    const ToolFrame frame(tool, at);
    const std::optional<PlacedContours> contours = place_contours(tin, tool, frame);
    if (!contours) return report;  // the tool misses the terrain
    const std::vector<Vec2>& outer = contours->outer;
    report.applied = true;
    const Generation generation = context.next_generation();
    report.generation = generation;
    const SculptSettings& settings = context.settings;
    LocateHint* hint = &context.hint;
    const double ledger_start = tin.volume_ledger();
    EditReport edit;
    const Imprint imprint(frame, tool.spec().mode == ImprintMode::Dig);
    // The rim tolerance scales with the tool (1 % of its radius by default), so on its own it
    // would let a big tool pressed in shallower than that change nothing at all (a 1.5 m tool
    // 1 cm deep). Relief below the simplification tolerance d_m is not worth enforcing either
    // (the simplifier would take it away): the smaller of the two decides.
    const double tolerance = std::min(tool.rim_tolerance(), settings.simplify.tolerance);

    // 1. Sample the contours, 2. find their active segments: the terrain as it was.
    const ContourSamples samples =
        sample_contours(tin, tool, at, *contours, imprint, settings.simplify.tolerance, hint);
    std::optional<ActiveSegments> active =
        find_active_segments(tin, tool, at.centre, samples, imprint, tolerance, generation, hint);
    if (!active) {  // the terrain already holds this imprint
        report.enforce_ms = elapsed_ms(t0);
        return report;
    }
    // 3. Fence. A fenced terrain gets all of O constrained, not only the parts next to an
    //    active I: the release's flips inside O must not leave through an unconstrained stretch.
    const PolygonInclusion in_outer(outer, at.centre);
    const RimFence fence =
        fence_rim(tin, tool, outer, samples, in_outer, tolerance, generation, settings, hint, edit);
    report.edges_fenced = fence.edges_fenced;
    if (fence.edges_fenced > 0) std::fill(active->rim.begin(), active->rim.end(), 1);
    const Band band(samples, *active);
    const PolygonInclusion in_inner(samples.inner, at.centre);
    // 4. Clear.
    report.cleared = clear_replaced_sand(tin, tool, outer, samples, *active, band, in_outer,
                                         in_inner, imprint, settings, hint, edit);
    // 5. Enforce O.
    report.retriangulation_volume = enforce_rim(tin, samples, *active, generation, hint, edit);
    // 6. Release.
    const Release release =
        release_under_footprint(tin, outer, generation, settings.keep_generations, edit);
    report.constraints_released = release.constraints;
    context.simplifier.enqueue(release.vertices);
    // 7. Enforce I, at the imprint's heights.
    enforce_contour(tin, samples.inner, samples.inner_h, active->inner, generation, hint, edit);
    // 8. Imprint.
    std::vector<VertexId> region =
        imprint_inside(tin, samples, in_inner, imprint, settings.simplify.tolerance, hint, edit);
    // 9. Clean the band. Then vertices a rounding error apart (left where nearly coincident old
    //    rims were crossed), which can fall on both sides of the contour and get different
    //    heights, a vertical sliver, take the lower height.
    std::vector<VertexId> footprint =
        clean_band(tin, samples, *active, band, in_outer, in_inner, imprint, region, hint, edit);
    if (imprint.dig()) equalise_slivers(tin, footprint, true);
    report.displaced_volume = -(tin.volume_ledger() - ledger_start);
    report.enforce_ms = elapsed_ms(t0);

    // 10. Simplify.
    const auto t1 = std::chrono::steady_clock::now();
    report.simplify =
        simplify_footprint(tin, tool, at.bottom, in_inner, region, std::move(footprint), context);
    report.simplify_ms = elapsed_ms(t1);

    // 11. Extrude; on a fenced terrain the ridge's band is enclosed too.
    const auto t2 = std::chrono::steady_clock::now();
    std::optional<RidgeFence> ridge_fence;
    if (fence.coarse_terrain) ridge_fence = RidgeFence{tolerance, generation - 1};
    const Extrusion extrusion = extrude(tin, tool, samples, outer, report.displaced_volume,
                                        report.retriangulation_volume, motion, ridge_fence, hint);
    report.deposited_volume = extrusion.deposited;
    report.undeposited_volume = extrusion.undeposited;
    report.edges_fenced += extrusion.edges_fenced;
    context.simplifier.enqueue(extrusion.ridge);
    report.extrude_ms = elapsed_ms(t2);

    report.volume_change = tin.volume_ledger() - ledger_start;
    report.triangles_touched = edit.triangles_changed;
    report.vertices_inserted = edit.vertices_created;
    report.vertices_removed = edit.vertices_removed + report.simplify.removed;
    return report;
}

}  // namespace sandtin
