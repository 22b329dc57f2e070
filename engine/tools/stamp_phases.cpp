// The phases of a stamp that edit the TIN, from fencing the rim to extrusion (phases 3 to 11 of
// tools/stamp.hpp).

#include "tools/detail/stamp_phases.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "tools/straying_samples.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin::detail {

namespace {

bool all_set(const std::vector<std::uint8_t>& flags) {
    return std::all_of(flags.begin(), flags.end(), [](std::uint8_t a) { return a != 0; });
}

/// Whether the edge from v to its neighbour w may border a patch cleared before the imprint:
/// the patch's hole is re-triangulated flat, which is right only where the imprint leaves the
/// surface flat on both sides of the edge.
bool may_border_cleared(const Tin& tin, const ContourSamples& s,
                        const std::vector<std::uint8_t>& inner_active,
                        const std::vector<std::uint8_t>& on_profile,
                        const PolygonInclusion& in_inner, const Imprint& imprint, VertexId v,
                        VertexId w) {
    const VertexArrays& va = tin.vertices();
    const std::vector<Vec2>& inner = s.inner;
    const Vec2 pv = va.position[v.value];
    if (!in_inner.contains(pv)) return true;  // a wall-band vertex
    const Vec2 pw = va.position[w.value];
    if (in_inner.contains(pw)) {
        return imprint(pw, va.height[w.value]) == imprint.frame().underside(pw);
    }
    // Across I: only through an enforced segment whose ends sit on the profile.
    for (std::size_t k = 0; k < inner.size(); ++k) {
        const std::size_t next = (k + 1) % inner.size();
        if ((!inner_active[k] || !on_profile[k] || !on_profile[next]) &&
            segments_intersect(pv, pw, inner[k], inner[next])) {
            return false;
        }
    }
    return true;
}

/// The height of the wall a digging tool leaves at p, between the contours and off O, or
/// nullopt where it has none (no contact, or p on O itself).
std::optional<double> wall_height(const Tin& tin, const ContourSamples& s,
                                  const std::vector<std::uint8_t>& inner_active,
                                  const Band::Position& band, const ToolFrame& frame, Vec2 p) {
    const NearestEdge& to_rim = band.to_rim;
    const std::size_t nearest_rim = to_rim.index;
    const double d_inner = band.to_inner.distance;
    const double d_outer = to_rim.distance;
    const double rim_height = (1.0 - to_rim.t) * s.rim_h[nearest_rim] +
                              to_rim.t * s.rim_h[(nearest_rim + 1) % s.rim.size()];
    const double profile = frame.underside(p);
    if (!std::isfinite(profile) || !(d_inner + d_outer > 0.0)) return std::nullopt;
    // A vertex on O itself (where O crossed a fenced edge, at that edge's height) is the terrain
    // the rim follows, which may stand off the chord between rim samples by up to the rim
    // tolerance.
    if (d_outer <= tin.snap_distance()) return std::nullopt;
    // Where I is enforced next to the vertex, the wall is the new surface: the ramp from I's
    // constrained heights to the rim. Elsewhere nothing re-forms the surface, and only sand
    // above the tool's own wall (its edge at I, sloping to the rim) is pushed down. Taking the
    // lower of the tool and the rim at I everywhere cut a hilltop stamp's untouched sand between
    // the contours, below the tool, by 2 mm.
    const NearestEdge& to_inner = band.to_inner;
    const std::size_t next = (to_inner.index + 1) % s.inner.size();
    const double inner_end =
        inner_active[to_inner.index]
            ? (1.0 - to_inner.t) * s.inner_h[to_inner.index] + to_inner.t * s.inner_h[next]
            : profile;
    return (d_outer * inner_end + d_inner * rim_height) / (d_inner + d_outer);
}

/// A flat tool that lowered everything it covers leaves one planar patch: it is removed in a
/// single step, without testing each vertex (the cost stays near-independent of how dense the
/// terrain was under the tool). nullopt when the floor is not level or not removed.
std::optional<SimplifyReport> remove_level_floor(Tin& tin, double bottom,
                                                 const PolygonInclusion& in_inner,
                                                 const std::vector<VertexId>& region,
                                                 const SculptSettings& settings) {
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> interior;
    for (VertexId v : region) {
        if (va.height[v.value] != bottom && in_inner.contains(va.position[v.value])) {
            return std::nullopt;
        }
        if (!tin.is_on_constraint(v) && !tin.is_boundary(v) &&
            in_inner.contains(va.position[v.value])) {
            interior.push_back(v);
        }
    }
    if (interior.empty()) return std::nullopt;
    EditReport patch;
    if (!tin.remove_planar_patch(interior, settings.simplify.tolerance,
                                 settings.simplify.volume_policy, &patch)) {
        return std::nullopt;
    }
    SimplifyReport r;
    r.tested += interior.size();
    r.removed += interior.size();
    r.volume_change += patch.volume_change;
    r.max_volume_change = std::abs(patch.volume_change);
    return r;
}

}  // namespace

RimFence fence_rim(Tin& tin, const Tool& tool, const std::vector<Vec2>& outer,
                   const ContourSamples& samples, const PolygonInclusion& in_outer,
                   double tolerance, Generation generation, const SculptSettings& settings,
                   LocateHint* hint, EditReport& edit) {
    // - Only where O crosses edges less than 8 times per tool width: sand sculpted at the
    //   tool's scale has its re-triangulation's detail already, and looking cost a stamp 9 % at
    //   10^6 points.
    // - Every bent edge, however short: a tool as wide as the terrain's triangles re-shapes them
    //   too (fencing only edges longer than the tool left a 20 m tool on 25 m triangles moving
    //   the surface 2.9 m outside O).
    const double perimeter = polygon_perimeter(outer);
    const double tool_width = 2.0 * tool.shape().bounding_radius;
    const bool coarse = 8.0 * perimeter > tool_width * static_cast<double>(samples.rim_crossings);
    RimFence fence;
    fence.coarse_terrain = settings.fence_coarse_edges && coarse;
    if (!fence.coarse_terrain) return fence;
    const std::vector<Vec2>& rim = samples.rim;
    std::vector<std::array<Vec2, 2>> spans;
    for (std::size_t k = 0; k < rim.size(); ++k)
        spans.push_back({rim[k], rim[(k + 1) % rim.size()]});
    // - One generation older than the stamp: the release after O is constrained frees them
    //   inside O; outside they stay until a later footprint or their expiry frees them.
    fence.edges_fenced =
        tin.fence_bent_edges(rim, spans, tolerance, generation - 1, &in_outer, hint, &edit);
    return fence;
}

Band::Band(const ContourSamples& samples, const ActiveSegments& active)
    : samples_(&samples),
      active_(&active),
      all_active_(all_set(active.inner) && all_set(active.rim)) {}

Band::Position Band::position(Vec2 p) const {
    Position b{nearest_edge(p, samples_->inner), nearest_edge(p, samples_->rim), false};
    b.both_active = active_->inner[b.to_inner.index] && active_->rim[b.to_rim.index];
    return b;
}

BulkRemoval clear_replaced_sand(Tin& tin, const Tool& tool, const std::vector<Vec2>& outer,
                                const ContourSamples& samples, const ActiveSegments& active,
                                const Band& band, const PolygonInclusion& in_outer,
                                const PolygonInclusion& in_inner, const Imprint& imprint,
                                const SculptSettings& settings, LocateHint* hint,
                                EditReport& edit) {
    // Whether enough vertices could qualify to be worth the walk that finds them: a segment of
    // length L crosses about 1.08 sqrt(rho) L edges of a Delaunay triangulation of density rho
    // (Poisson points), so the rim's crossings estimate the vertices inside O.
    const double perimeter = polygon_perimeter(outer);
    const double per_metre =
        perimeter > 0.0 ? static_cast<double>(samples.rim_crossings) / perimeter : 0.0;
    const double density = (per_metre / 1.08) * (per_metre / 1.08);
    const double expected_inside = density * std::abs(signed_area(outer));
    // Only part of O's inside is fresh sand along a stroke, hence the factor (calibrated on the
    // groove: at 10^5 points the walk found too few vertices to clear, at 10^6 hundreds).
    if (!settings.clear_before_imprint ||
        !(expected_inside >= 4.0 * static_cast<double>(settings.min_bulk_clearing))) {
        return {};
    }
    const bool clear_inside = tool.profile().is_flat() && settings.simplify_after_edit;
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> doomed;
    for (VertexId v : tin.vertices_in_polygon(in_outer, hint)) {
        const Vec2 p = va.position[v.value];
        if (in_inner.contains(p)) {
            const double h = va.height[v.value];
            if (clear_inside && imprint(p, h) != h) doomed.push_back(v);
        } else if (band.both_active_at(p)) {
            doomed.push_back(v);
        }
    }
    // A few vertices cost more to clear in patches (a hole triangulation per patch) than the
    // plain path spends crossing them (SculptSettings::min_bulk_clearing).
    if (doomed.size() < settings.min_bulk_clearing) return {};
    const std::vector<Vec2>& inner = samples.inner;
    std::vector<std::uint8_t> on_profile(inner.size());
    for (std::size_t k = 0; k < inner.size(); ++k)
        on_profile[k] = samples.inner_h[k] == imprint.frame().underside(inner[k]) ? 1 : 0;
    return remove_in_patches(tin, doomed, &edit, [&](VertexId v, VertexId w) {
        return may_border_cleared(tin, samples, active.inner, on_profile, in_inner, imprint, v, w);
    });
}

void enforce_contour(Tin& tin, const std::vector<Vec2>& points, const std::vector<double>& heights,
                     const std::vector<std::uint8_t>& active, Generation generation,
                     LocateHint* hint, EditReport& edit) {
    const std::size_t n = points.size();
    std::vector<std::size_t> index(n, SIZE_MAX);
    std::vector<Vec2> ps;
    std::vector<double> zs;
    for (std::size_t k = 0; k < n; ++k) {
        if (active[k] || active[(k + n - 1) % n]) {
            index[k] = ps.size();
            ps.push_back(points[k]);
            zs.push_back(heights[k]);
        }
    }
    const std::vector<VertexId> ids = tin.insert_points(ps, zs, hint, &edit);
    std::vector<std::array<VertexId, 2>> segments;
    for (std::size_t k = 0; k < n; ++k) {
        if (!active[k]) continue;
        const VertexId a = ids[index[k]];
        const VertexId b = ids[index[(k + 1) % n]];
        if (a != b) segments.push_back({a, b});
    }
    tin.insert_constraints(segments, generation, VolumePolicy::Report, &edit);
}

double enforce_rim(Tin& tin, const ContourSamples& samples, const ActiveSegments& active,
                   Generation generation, LocateHint* hint, EditReport& edit) {
    // O's points go in at the terrain's own heights, so the volume this changes is that of
    // re-triangulating around them.
    EditReport rim_edit;
    enforce_contour(tin, samples.rim, samples.rim_h, active.rim, generation, hint, rim_edit);
    edit.accumulate(rim_edit);
    return rim_edit.volume_change;
}

Release release_under_footprint(Tin& tin, const std::vector<Vec2>& outer, Generation generation,
                                Generation keep_generations, EditReport& edit) {
    Release release;
    ReleaseFilter under;
    under.older_than = generation;
    under.inside_polygon = outer;
    release.constraints +=
        tin.release_constraints(under, VolumePolicy::Report, &edit, &release.vertices);
    if (generation > keep_generations) {
        release.constraints += tin.expire_constraints(
            generation - keep_generations, VolumePolicy::Report, &edit, &release.vertices);
    }
    return release;
}

std::vector<VertexId> imprint_inside(Tin& tin, const ContourSamples& samples,
                                     const PolygonInclusion& in_inner, const Imprint& imprint,
                                     double simplify_tolerance, LocateHint* hint,
                                     EditReport& edit) {
    // Also a vertex of the terrain that lay on I already (I's own points went in at the
    // profile's height): a grid terrain under a tool at round coordinates has them on its edges
    // and corners, and a level stamp left their triangles as wedges off the level inside the
    // footprint.
    const VertexArrays& va = tin.vertices();
    const std::vector<Vec2>& inner = samples.inner;
    std::vector<VertexId> region = tin.vertices_in_region(interior_seeds(inner), inner, hint);
    for (VertexId v : region) {
        const Vec2 p = va.position[v.value];
        if (!in_inner.contains(p) &&
            !(tin.is_on_constraint(v) && nearest_edge(p, inner).distance <= tin.snap_distance())) {
            continue;
        }
        const double h = imprint(p, va.height[v.value]);
        if (h != va.height[v.value]) tin.set_height(v, h);
    }
    // A curved profile's lattice adds vertices where the surface now strays from the imprint
    // by more than half the simplification tolerance (the simplifier may later take up to the
    // tolerance itself), coarse to fine (straying_samples.hpp).
    const ProfileLattice& lattice = samples.lattice;
    if (!lattice.points.empty()) {
        std::vector<double> lattice_h(lattice.points.size());
        for (std::size_t i = 0; i < lattice.points.size(); ++i)
            lattice_h[i] = imprint.under(lattice.underside[i], lattice.terrain[i]);
        const std::vector<VertexId> added = insert_straying_samples(
            tin, lattice.points, lattice_h, 0.5 * simplify_tolerance, hint, &edit);
        region.insert(region.end(), added.begin(), added.end());
    }
    return region;
}

std::vector<VertexId> clean_band(Tin& tin, const ContourSamples& samples,
                                 const ActiveSegments& active, const Band& band,
                                 const PolygonInclusion& in_outer, const PolygonInclusion& in_inner,
                                 const Imprint& imprint, std::vector<VertexId>& region,
                                 LocateHint* hint, EditReport& edit) {
    // Where both contours are constrained next to them the band's old vertices are removed, so
    // the wall is the ramp from the profile at I to the rim at O and nothing else (re-working a
    // trail would otherwise pile old rims up in the walls, where no planarity test can ever
    // remove them). Elsewhere a digging tool brings them down to that ramp, so they cannot poke
    // up through the new wall. One walk over the faces under O serves the band, the slivers and
    // the footprint's re-simplification: after this point the stamp only removes vertices.
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> footprint;
    std::vector<VertexId> band_junk;
    for (VertexId v : tin.vertices_in_polygon(in_outer, hint)) {
        const Vec2 p = va.position[v.value];
        footprint.push_back(v);
        if (in_inner.contains(p)) continue;
        if (band.both_active_at(p) && !tin.is_on_constraint(v) && !tin.is_boundary(v)) {
            band_junk.push_back(v);
            continue;
        }
        if (!imprint.dig()) continue;
        const std::optional<double> wall =
            wall_height(tin, samples, active.inner, band.position(p), imprint.frame(), p);
        if (wall && va.height[v.value] > *wall) tin.set_height(v, *wall);
    }
    for (VertexId v : band_junk)
        tin.remove_vertex(v, VolumePolicy::Report, &edit);
    // The region's walk also collected the corners of faces reaching into the band.
    if (!band_junk.empty()) {
        std::erase_if(region, [&](VertexId v) { return !tin.is_alive(v); });
        std::erase_if(footprint, [&](VertexId v) { return !tin.is_alive(v); });
    }
    return footprint;
}

SimplifyReport simplify_footprint(Tin& tin, const Tool& tool, double bottom,
                                  const PolygonInclusion& in_inner,
                                  const std::vector<VertexId>& region,
                                  std::vector<VertexId> footprint, SculptContext& context) {
    const SculptSettings& settings = context.settings;
    SimplifyReport report;
    // Inner vertices that the flat imprint made redundant go at once; the rest of the queue
    // (released rims, earlier edits) is processed too: this is the end of the iteration.
    std::optional<SimplifyReport> floor;
    if (tool.profile().is_flat() && settings.simplify_after_edit && region.size() > 1) {
        floor = remove_level_floor(tin, bottom, in_inner, region, settings);
    }
    if (floor) {
        report = *floor;
    } else {
        context.simplifier.enqueue(region);
    }
    // The rest of the footprint too: a vertex of an older rim inside O may have become
    // redundant now that the new contours run next to it (re-working a trail leaves such rims
    // behind on every pass), although its height did not change. Outside O nothing is touched.
    std::erase_if(footprint, [&](VertexId v) { return !tin.is_alive(v); });
    context.simplifier.enqueue(footprint);
    if (settings.simplify_after_edit) {
        report.accumulate(context.simplifier.run(tin, settings.simplify));
    }
    return report;
}

Extrusion extrude(Tin& tin, const Tool& tool, const ContourSamples& samples,
                  const std::vector<Vec2>& outer, double displaced_volume,
                  double retriangulation_volume, std::optional<Vec2> motion,
                  const std::optional<RidgeFence>& fence, LocateHint* hint) {
    // The ridge carries what the tool cut, and the volume re-triangulating around the rim
    // changed, so that the stamp conserves volume exactly: on sand sampled finely beside the
    // tool that is a few per cent of the cut, and no more than a layer far thinner than the
    // tool is wide over its footprint. Delaunay insertion re-triangulates every triangle whose
    // circumcircle holds a rim point: on a coarse, curved TIN (an imported elevation model)
    // that reaches far beyond the tool and changes more volume than a layer as thick as the
    // tool's radius over its footprint. That volume is no sand the tool moved: carried by the
    // ridge, it dug a band 100 m deep beside a 10 cm tool (6.5 m³ re-triangulated, 1.6 l cut,
    // on a 1 m-per-pixel import). It then stays where it happened, reported.
    const double tool_cut = displaced_volume + retriangulation_volume;
    const double carried =
        std::abs(retriangulation_volume) <= std::abs(signed_area(outer)) * tool.radius()
            ? retriangulation_volume
            : 0.0;
    const double to_deposit = tool_cut - carried;
    Extrusion extrusion;
    if (!tool.spec().extrude || to_deposit == 0.0) return extrusion;
    // Cut depth at each rim point: that of the nearest inner contour point.
    const std::vector<Vec2>& rim = samples.rim;
    const std::vector<Vec2>& inner = samples.inner;
    std::vector<double> cut(rim.size(), 0.0);
    for (std::size_t i = 0; i < rim.size(); ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < inner.size(); ++j) {
            const double d = length_squared(inner[j] - rim[i]);
            if (d < best) {
                best = d;
                cut[i] = samples.inner_terrain[j] - samples.inner_h[j];
            }
        }
    }
    const RidgeReport ridge =
        deposit_ridge(tin, rim, cut, motion, tool.extrusion_width(), to_deposit, hint,
                      &extrusion.ridge, fence ? &*fence : nullptr);
    extrusion.deposited = ridge.deposited;
    extrusion.edges_fenced = ridge.edges_fenced;
    extrusion.undeposited = to_deposit - ridge.deposited;
    return extrusion;
}

}  // namespace sandtin::detail
