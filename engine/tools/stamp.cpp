#include "tools/stamp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "tin/bulk_removal.hpp"
#include "tools/extrusion.hpp"
#include "tools/imprint_activity.hpp"
#include "tools/slivers.hpp"
#include "tools/straying_samples.hpp"

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

double elapsed_ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

/// Removes points closer than `eps` to their predecessor (clipping and subdivision can make
/// them), keeping the polygon closed.
std::vector<Vec2> drop_near_duplicates(std::vector<Vec2> pts, double eps) {
    std::vector<Vec2> out;
    for (Vec2 p : pts) {
        if (out.empty() || distance(out.back(), p) > eps) out.push_back(p);
    }
    while (out.size() > 1 && distance(out.front(), out.back()) <= eps)
        out.pop_back();
    return out;
}

double surface_or(const Tin& tin, Vec2 p, LocateHint* hint, double fallback) {
    const std::optional<double> h = tin.height_at(p, hint);
    return h ? *h : fallback;
}

/// Drapes the closed polygon over the terrain: along each edge, the crossings with triangle
/// edges where the surface bends by more than `tolerance` (Douglas-Peucker on the exact
/// section), so the rim follows the terrain within the tolerance with as few points as that
/// takes.
/// `crossings` counts the triangle edges the polygon crosses (a measure of the density under
/// it).
void sample_rim(const Tin& tin, std::span<const Vec2> polygon, double tolerance, double min_spacing,
                LocateHint* hint, std::vector<Vec2>& points, std::vector<double>& heights,
                std::size_t& crossings) {
    const std::size_t n = polygon.size();
    std::vector<std::pair<std::size_t, std::size_t>> stack;
    std::vector<std::uint8_t> keep;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = polygon[i];
        const Vec2 b = polygon[(i + 1) % n];
        const auto sec = tin.section(a, b, hint);
        crossings += sec.size() > 2 ? sec.size() - 2 : 0;
        const double min_dt = min_spacing / std::max(distance(a, b), 1e-300);
        keep.assign(sec.size(), 0);
        keep.front() = 1;
        keep.back() = 1;
        stack.clear();
        stack.emplace_back(0, sec.size() - 1);
        while (!stack.empty()) {
            const auto [lo, hi] = stack.back();
            stack.pop_back();
            if (hi <= lo + 1) continue;
            double worst = 0.0;
            std::size_t at = lo;
            for (std::size_t k = lo + 1; k < hi; ++k) {
                const double t = (sec[k].first - sec[lo].first) / (sec[hi].first - sec[lo].first);
                const double straight = (1.0 - t) * sec[lo].second + t * sec[hi].second;
                const double dev = std::abs(sec[k].second - straight);
                if (dev > worst) {
                    worst = dev;
                    at = k;
                }
            }
            // A crossing closer than min_spacing to a kept point would only make sliver
            // triangles (tiny vertices slow the relaxation down to their own scale).
            if (worst > tolerance && sec[at].first - sec[lo].first > min_dt &&
                sec[hi].first - sec[at].first > min_dt) {
                keep[at] = 1;
                stack.emplace_back(lo, at);
                stack.emplace_back(at, hi);
            }
        }
        for (std::size_t k = 0; k + 1 < sec.size(); ++k) {
            if (!keep[k]) continue;
            points.push_back(k == 0 ? a : lerp(a, b, sec[k].first));
            heights.push_back(sec[k].second);
        }
    }
}

/// The inner contour with the points its constrained chords need where the tool stands above
/// the sand: there the stamp leaves the sand as it is, and a chord between two of I's points
/// would cut through it or bridge over it. Along each edge the candidates are the terrain's
/// section points clear of the tool; Douglas-Peucker keeps those the chord (between kept points
/// at the imprint's heights) misses by more than `tolerance`, none closer than `min_spacing` to
/// a kept one. Where the tool touches, I keeps its own points, as before. Without them the
/// rake, whose I is enforced whole (its edges stand above the sand) with points 25 mm apart,
/// about its tine pitch, walled off the previous stamp's furrows with straight chords across
/// its back edge at the height of the sand between the tines: its strokes left rows of studs.
std::vector<Vec2> drape_inner(const Tin& tin, std::span<const Vec2> inner, const ToolFrame& frame,
                              bool dig, double tolerance, double min_spacing, LocateHint* hint) {
    struct Sample {
        double t;       ///< along the edge
        double height;  ///< what the stamp leaves there
        bool clear;     ///< the tool stands above the sand (or has no contact) there
    };
    const std::size_t n = inner.size();
    std::vector<Vec2> out;
    std::vector<Sample> samples;
    std::vector<std::uint8_t> keep;
    std::vector<std::pair<std::size_t, std::size_t>> stack;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = inner[i];
        const Vec2 b = inner[(i + 1) % n];
        out.push_back(a);
        const double len = distance(a, b);
        if (!(len > 2.0 * min_spacing)) continue;
        samples.clear();
        bool any_clear = false;
        for (const auto& [t, terrain] : tin.section(a, b, hint)) {
            const double u = frame.underside(lerp(a, b, t));
            const bool clear = !std::isfinite(u) || (dig && terrain <= u);
            samples.push_back({t, clear ? terrain : u, clear});
            any_clear = any_clear || clear;
        }
        if (!any_clear || samples.size() < 3) continue;
        const double min_dt = min_spacing / len;
        keep.assign(samples.size(), 0);
        stack.assign(1, {0, samples.size() - 1});
        while (!stack.empty()) {
            const auto [lo, hi] = stack.back();
            stack.pop_back();
            double worst = 0.0;
            std::size_t at = lo;
            for (std::size_t k = lo + 1; k < hi; ++k) {
                if (!samples[k].clear) continue;
                const double f = (samples[k].t - samples[lo].t) / (samples[hi].t - samples[lo].t);
                const double chord = (1.0 - f) * samples[lo].height + f * samples[hi].height;
                const double dev = std::abs(samples[k].height - chord);
                if (dev > worst) {
                    worst = dev;
                    at = k;
                }
            }
            if (worst > tolerance && samples[at].t - samples[lo].t > min_dt &&
                samples[hi].t - samples[at].t > min_dt) {
                keep[at] = 1;
                stack.emplace_back(lo, at);
                stack.emplace_back(at, hi);
            }
        }
        for (std::size_t k = 1; k + 1 < samples.size(); ++k) {
            if (keep[k]) out.push_back(lerp(a, b, samples[k].t));
        }
    }
    return out;
}

}  // namespace

StampReport stamp(Tin& tin, const Tool& tool, const ToolPlacement& at, SculptContext& context,
                  std::optional<Vec2> motion) {
    StampReport report;
    const auto t0 = std::chrono::steady_clock::now();
    if (!is_finite(at.centre) || !std::isfinite(at.angle) || !std::isfinite(at.bottom)) {
        throw std::invalid_argument("stamp: tool placement is not finite");
    }
    const Rect domain = tin.domain();
    // Points closer than the snap distance are one vertex: an inner contour that close to
    // the outer one would merge with the rim, and the stamp would dig nothing.
    if (!(tool.shape().gap > 4.0 * tin.snap_distance())) {
        const auto metres = [](double m) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g m", m);
            return std::string(text);
        };
        const double k = 4.0 * tin.snap_distance() / tool.shape().gap;
        throw std::invalid_argument(
            "stamp: the tool is too small for this terrain: its contours are " +
            metres(tool.shape().gap) + " apart, within four snap distances (" +
            metres(tin.snap_distance()) +
            " on a terrain this size), so the inner one would merge with the rim and dig "
            "nothing; use a radius of at least " +
            metres(k * tool.radius()) + ", or a gap above " + metres(4.0 * tin.snap_distance()));
    }
    const double spacing = tool.rim_spacing();
    const double eps = 1e-9 * std::max(tool.radius(), 1e-9);
    const ToolFrame frame(tool, at);
    auto to_world = [&](std::span<const Vec2> local) {
        std::vector<Vec2> out;
        for (Vec2 p : subdivide_contour(local, spacing))
            out.push_back(frame.to_world(p));
        return out;
    };
    std::vector<Vec2> outer = drop_near_duplicates(
        clip_to_rect(to_world(tool.shape().outer), domain.min, domain.max), eps);
    const std::vector<Vec2> inner_whole = to_world(tool.shape().inner);
    const bool inner_clipped = !std::all_of(inner_whole.begin(), inner_whole.end(),
                                            [&](Vec2 p) { return domain.contains(p); });
    std::vector<Vec2> inner =
        drop_near_duplicates(clip_to_rect(inner_whole, domain.min, domain.max), eps);
    if (outer.size() < 3 || inner.size() < 3 || !(std::abs(signed_area(inner)) > eps * eps)) {
        return report;  // the tool misses the terrain
    }
    report.applied = true;
    const Generation generation = context.next_generation();
    report.generation = generation;
    LocateHint* hint = &context.hint;
    const double ledger_start = tin.volume_ledger();
    EditReport edit;

    // 2. The terrain before the stamp: along the rim (adaptively), at the inner contour (with
    //    the points it needs to follow the imprint) and at the interior samples of a curved
    //    profile.
    const bool dig = tool.spec().mode == ImprintMode::Dig;
    // The rim tolerance scales with the tool (1 % of its radius by default), so on its own it
    // would let a big tool pressed in shallower than that change nothing at all (a 1.5 m tool
    // 1 cm deep). Relief below the simplification tolerance d_m is not worth enforcing either
    // (the simplifier would take it away): the smaller of the two decides.
    const double tol = std::min(tool.rim_tolerance(), context.settings.simplify.tolerance);
    std::vector<Vec2> rim;
    std::vector<double> rim_h;
    const double min_spacing = 0.25 * tool.shape().gap;
    // I follows the sand the tool stands above to the coarser of the rim's tolerance and the
    // simplifier's: a floor the simplifier's volume-conserving shifts left a hair below the
    // tool (re-working a trail) is no sand to follow, and chasing it at the rim's 1 % of a small
    // tool's radius made a 10^5-stamp stroke's vertices grow without end.
    inner = drape_inner(tin, inner, frame, dig,
                        std::max(tool.rim_tolerance(), context.settings.simplify.tolerance),
                        min_spacing, hint);
    std::size_t rim_crossings = 0;
    sample_rim(tin, outer, tool.rim_tolerance(), min_spacing, hint, rim, rim_h, rim_crossings);
    std::vector<double> inner_terrain(inner.size());
    for (std::size_t i = 0; i < inner.size(); ++i)
        inner_terrain[i] = surface_or(tin, inner[i], hint, 0.0);
    // A curved profile's interior samples, with the underside's height at each.
    std::vector<Vec2> lattice;
    std::vector<double> lattice_underside;
    std::vector<double> lattice_terrain;
    if (!tool.profile().is_flat()) {
        const Tool::InteriorSamples& samples = tool.interior_samples();
        if (inner_clipped) {
            // Part of I lies outside the domain: a lattice of the clipped contour. (The tool's
            // own lattice with the samples past the border left out leaves a wider strip
            // unsampled there: the ball then missed its imprint by 1.2 mm 2 mm from the
            // border, against the 1 mm its test allows.)
            lattice = interior_lattice(inner, samples.spacing);
            // The lattice keeps half a spacing from every edge, the stretch along the domain's
            // border too, where the profile does not drop to the rim as it does along the
            // tool's outline: samples on that stretch as well, one spacing apart. (Without
            // them the border between I's two corners there only interpolated those corners:
            // a ball or foot pressed at the border of a terrain with no vertices along it
            // missed its imprint by up to 14 mm on the border line.)
            const std::vector<Vec2> along_border =
                samples_along_sides(inner, domain, samples.spacing);
            lattice.insert(lattice.end(), along_border.begin(), along_border.end());
            for (Vec2 p : lattice)
                lattice_underside.push_back(frame.underside(p));
        } else {
            lattice.reserve(samples.local.size());
            for (Vec2 p : samples.local)
                lattice.push_back(frame.to_world(p));
            for (double offset : samples.offset)
                lattice_underside.push_back(at.bottom + offset);
        }
        lattice_terrain.resize(lattice.size());
        tin.heights_at(lattice, lattice_terrain, hint);
        for (double& h : lattice_terrain) {
            if (std::isnan(h)) h = 0.0;  // outside the domain, as surface_or
        }
    }
    // The height the stamp leaves where its underside is at height u and the sand at `terrain`.
    auto imprint_under = [&](double u, double terrain) {
        if (!std::isfinite(u)) return terrain;  // no contact there
        return dig ? std::min(terrain, u) : u;
    };
    auto imprint = [&](Vec2 p, double terrain) {
        return imprint_under(frame.underside(p), terrain);
    };

    // Which parts of the contours the stamp actually changes: an inner segment is active
    // where the terrain along it (pre-stamp) stands off the tool by more than the tolerance;
    // an outer segment is kept next to an active inner one. Along the trail of a stroke the
    // trailing half of each contour lies in sand already dug to the tool's depth, and
    // constraining it would only create vertices the next stamp removes again.
    std::vector<double> inner_h(inner.size());
    for (std::size_t i = 0; i < inner.size(); ++i)
        inner_h[i] = imprint(inner[i], inner_terrain[i]);
    // Which parts of I would move sand (imprint_activity.hpp); none at all: the terrain already
    // holds this imprint (re-working a trail), and the stamp changes nothing, so it adds no
    // vertices, constraints or releases either.
    const double lateral = tool.shape().gap;
    const ImprintActivity activity =
        inner_contour_activity(tin, inner, imprint, tol, lateral, hint);
    std::vector<std::uint8_t> inner_active = activity.inner_active;
    bool acts = activity.any_segment;
    // A curved profile also acts inside I: its interior samples decide too.
    for (std::size_t k = 0; k < lattice.size() && !acts; ++k)
        acts = std::abs(lattice_terrain[k] -
                        imprint_under(lattice_underside[k], lattice_terrain[k])) > tol;
    if (!acts && !interior_stands_off(tin, inner, imprint, tol, lateral, at.centre,
                                      tool.shape().bounding_radius, hint)) {
        report.enforce_ms = elapsed_ms(t0);
        return report;
    }
    // A tool that cuts only inside I (a wide tool pressed into a hilltop) still needs its
    // footprint: without its contours, the triangles from the lowered sand inside I reached
    // past O and tilted the surface there (1.9 mm, 7.7 cm beyond O). Its I and O are
    // enforced whole, I at the sand's own height where the tool stands above it.
    if (!activity.any_segment) std::fill(inner_active.begin(), inner_active.end(), 1);
    std::vector<std::uint8_t> rim_active(rim.size(), 0);
    const double reach = tool.shape().gap + spacing;
    for (std::size_t k = 0; k < rim.size(); ++k) {
        const Vec2 a = rim[k];
        const Vec2 b = rim[(k + 1) % rim.size()];
        for (std::size_t i = 0; i < inner.size() && !rim_active[k]; ++i) {
            if (!inner_active[i]) continue;
            const Vec2 c = inner[i];
            const Vec2 d = inner[(i + 1) % inner.size()];
            const double gap =
                std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                          distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
            rim_active[k] = gap <= reach ? 1 : 0;
        }
    }
    // An outer segment crossed by an older constraint is constrained too: the release below
    // splits that constraint where O crosses it, and a constrained O keeps the release's flips
    // from reaching the older imprint outside.
    const std::vector<std::array<Vec2, 2>> older =
        tin.constrained_segments(bounding_box(std::span<const Vec2>(rim)), generation);
    for (std::size_t k = 0; k < rim.size(); ++k) {
        if (rim_active[k]) continue;
        const Vec2 a = rim[k];
        const Vec2 b = rim[(k + 1) % rim.size()];
        for (const auto& seg : older) {
            if (segments_intersect(a, b, seg[0], seg[1])) {
                rim_active[k] = 1;
                break;
            }
        }
    }
    // Before anything changes: the bent edges that inserting O would re-triangulate are
    // constrained (Tin::fence_bent_edges), so the surface outside O stays as it was, and where
    // O crosses them it takes the terrain's own height there (after the bulk clearing below, an
    // edge across the cleared sand would give it the cleared surface's height).
    // - Only where O crosses edges less than 8 times per tool width: sand sculpted at the
    //   tool's scale has its re-triangulation's detail already, and looking cost a stamp 9 % at
    //   10^6 points.
    // - Every bent edge, however short: a tool as wide as the terrain's triangles re-shapes
    //   them too (fencing only edges longer than the tool left a 20 m tool on 25 m triangles
    //   moving the surface 2.9 m outside O).
    // - One generation older than the stamp: the release after O is constrained frees them
    //   inside O; outside they stay until a later footprint or their expiry frees them.
    // - A fenced terrain gets all of O constrained, not only the parts next to an active I: the
    //   release's flips inside O must not leave through an unconstrained stretch of it.
    const PolygonInclusion in_outer(outer, at.centre);
    const double perimeter = polygon_perimeter(outer);
    const double tool_width = 2.0 * tool.shape().bounding_radius;
    const bool coarse = 8.0 * perimeter > tool_width * static_cast<double>(rim_crossings);
    const bool fenced_terrain = context.settings.fence_coarse_edges && coarse;
    if (fenced_terrain) {
        std::vector<std::array<Vec2, 2>> spans;
        for (std::size_t k = 0; k < rim.size(); ++k)
            spans.push_back({rim[k], rim[(k + 1) % rim.size()]});
        report.edges_fenced =
            tin.fence_bent_edges(rim, spans, tol, generation - 1, &in_outer, hint, &edit);
        if (report.edges_fenced > 0) std::fill(rim_active.begin(), rim_active.end(), 1);
    }
    // Inserts the endpoints of the active segments of a closed contour and constrains them,
    // adding what that did to `into`.
    auto enforce = [&](const std::vector<Vec2>& pts, const std::vector<double>& hs,
                       const std::vector<std::uint8_t>& active, EditReport& into) {
        const std::size_t n = pts.size();
        std::vector<std::size_t> index(n, SIZE_MAX);
        std::vector<Vec2> ps;
        std::vector<double> zs;
        for (std::size_t k = 0; k < n; ++k) {
            if (active[k] || active[(k + n - 1) % n]) {
                index[k] = ps.size();
                ps.push_back(pts[k]);
                zs.push_back(hs[k]);
            }
        }
        const std::vector<VertexId> ids = tin.insert_points(ps, zs, hint, &into);
        std::vector<std::array<VertexId, 2>> segments;
        for (std::size_t k = 0; k < n; ++k) {
            if (!active[k]) continue;
            const VertexId a = ids[index[k]];
            const VertexId b = ids[index[(k + 1) % n]];
            if (a != b) segments.push_back({a, b});
        }
        tin.insert_constraints(segments, generation, VolumePolicy::Report, &into);
    };

    // Where a point between the contours sits relative to them: its nearest I and rim
    // segments, and whether both are enforced (then the wall there is just the I-to-O ramp).
    struct BandPosition {
        NearestEdge to_inner;
        NearestEdge to_rim;
        bool both_active = false;
    };
    auto band_position = [&](Vec2 p) {
        BandPosition b{nearest_edge(p, inner), nearest_edge(p, rim), false};
        b.both_active = inner_active[b.to_inner.index] && rim_active[b.to_rim.index];
        return b;
    };
    // Whether a point's nearest segments are both enforced, without looking for them when every
    // segment of both contours is (the common case of a stamp into sand).
    const bool all_active =
        std::all_of(inner_active.begin(), inner_active.end(),
                    [](std::uint8_t a) { return a != 0; }) &&
        std::all_of(rim_active.begin(), rim_active.end(), [](std::uint8_t a) { return a != 0; });
    auto both_active_at = [&](Vec2 p) { return all_active || band_position(p).both_active; };
    const VertexArrays& va = tin.vertices();
    const PolygonInclusion in_inner(inner, at.centre);

    // Sand the imprint is about to replace goes first, in bulk (tin/bulk_removal.hpp). The contours
    // then cross a few long triangles instead of every triangle of dense sand. Only vertices
    // that the stamp would remove anyway go, so the vertices left, and with them the
    // constrained Delaunay triangulation and the surface, are the same as without this step (a
    // test compares both paths; the terrain along the contours was sampled above):
    // - in the wall band next to enforced contours, every unconstrained vertex (removed below);
    // - under a flat profile, with simplification on, a vertex the imprint moves, when all its
    //   neighbours end on the floor too or lie across an enforced part of I: its star is then
    //   flat after the stamp, and the simplifier would remove it.
    // Whether enough vertices could qualify to be worth the walk that finds them: a segment of
    // length L crosses about 1.08 sqrt(rho) L edges of a Delaunay triangulation of density rho
    // (Poisson points), so the rim's crossings estimate the vertices inside O.
    const double per_metre = perimeter > 0.0 ? static_cast<double>(rim_crossings) / perimeter : 0.0;
    const double density = (per_metre / 1.08) * (per_metre / 1.08);
    const double expected_inside = density * std::abs(signed_area(outer));
    // Only part of O's inside is fresh sand along a stroke, hence the factor (calibrated on the
    // groove: at 10^5 points the walk found too few vertices to clear, at 10^6 hundreds).
    if (context.settings.clear_before_imprint &&
        expected_inside >= 4.0 * static_cast<double>(context.settings.min_bulk_clearing)) {
        const bool clear_inside = tool.profile().is_flat() && context.settings.simplify_after_edit;
        std::vector<VertexId> doomed;
        for (VertexId v : tin.vertices_in_polygon(in_outer, hint)) {
            const Vec2 p = va.position[v.value];
            if (in_inner.contains(p)) {
                const double h = va.height[v.value];
                if (clear_inside && imprint(p, h) != h) doomed.push_back(v);
            } else if (both_active_at(p)) {
                doomed.push_back(v);
            }
        }
        // A few vertices cost more to clear in patches (a hole triangulation per patch) than
        // the plain path spends crossing them (SculptSettings::min_bulk_clearing).
        if (doomed.size() >= context.settings.min_bulk_clearing) {
            std::vector<std::uint8_t> on_profile(inner.size());
            for (std::size_t k = 0; k < inner.size(); ++k)
                on_profile[k] = inner_h[k] == frame.underside(inner[k]) ? 1 : 0;
            auto may_border = [&](VertexId v, VertexId w) {
                const Vec2 pv = va.position[v.value];
                if (!in_inner.contains(pv)) return true;  // a wall-band vertex
                const Vec2 pw = va.position[w.value];
                if (in_inner.contains(pw)) {
                    return imprint(pw, va.height[w.value]) == frame.underside(pw);
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
            };
            report.cleared = remove_in_patches(tin, doomed, &edit, may_border);
        }
    }

    // 3. Outer contour at the terrain's heights.
    // Its points go in at the terrain's own heights, so the volume this changes is that of
    // re-triangulating around them (see step 7).
    EditReport rim_edit;
    enforce(rim, rim_h, rim_active, rim_edit);
    report.retriangulation_volume = rim_edit.volume_change;
    edit.accumulate(rim_edit);

    // Older constraints inside the footprint are released now that O is constrained: a
    // constraint crossing O was split where O crossed it, its outside part keeps its
    // constraint, and the Delaunay flips of the release stay inside O. Constraints past their
    // lifetime go wherever they are, but only where releasing them re-triangulates nothing.
    std::vector<VertexId> released;
    ReleaseFilter under;
    under.older_than = generation;
    under.inside_polygon = outer;
    report.constraints_released +=
        tin.release_constraints(under, VolumePolicy::Report, &edit, &released);
    if (generation > context.settings.keep_generations) {
        report.constraints_released += tin.expire_constraints(
            generation - context.settings.keep_generations, VolumePolicy::Report, &edit, &released);
    }
    context.simplifier.enqueue(released);

    // 4. Inner contour at the profile's heights.
    enforce(inner, inner_h, inner_active, edit);

    // 5. Every vertex inside I follows the profile, and so does one of the terrain that lay
    //    on I already (I's own points went in at the profile's height): a grid terrain under
    //    a tool at round coordinates has them on its edges and corners, and a level stamp
    //    left their triangles as wedges off the level inside the footprint.
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
    if (!lattice.empty()) {
        std::vector<double> lattice_h(lattice.size());
        for (std::size_t i = 0; i < lattice.size(); ++i)
            lattice_h[i] = imprint_under(lattice_underside[i], lattice_terrain[i]);
        const std::vector<VertexId> added = insert_straying_samples(
            tin, lattice, lattice_h, 0.5 * context.settings.simplify.tolerance, hint, &edit);
        region.insert(region.end(), added.begin(), added.end());
    }
    // Vertices left in the thin band between I and O by earlier edits: where both contours
    // are constrained next to them they are removed, so the wall is the ramp from the profile
    // at I to the rim at O and nothing else (re-working a trail would otherwise pile old rims
    // up in the walls, where no planarity test can ever remove them). Elsewhere a digging
    // tool brings them down to that ramp, so they cannot poke up through the new wall.
    // One walk over the faces under O serves the band, the slivers and the footprint's
    // re-simplification below: after this point the stamp only removes vertices.
    std::vector<VertexId> footprint;
    {
        std::vector<VertexId> band_junk;
        for (VertexId v : tin.vertices_in_polygon(in_outer, hint)) {
            const Vec2 p = va.position[v.value];
            footprint.push_back(v);
            if (in_inner.contains(p)) continue;
            if (both_active_at(p) && !tin.is_on_constraint(v) && !tin.is_boundary(v)) {
                band_junk.push_back(v);
                continue;
            }
            if (!dig) continue;
            const BandPosition band = band_position(p);
            const NearestEdge& to_rim = band.to_rim;
            const std::size_t nearest_rim = to_rim.index;
            const double d_inner = band.to_inner.distance;
            const double d_outer = to_rim.distance;
            const double rim_height = (1.0 - to_rim.t) * rim_h[nearest_rim] +
                                      to_rim.t * rim_h[(nearest_rim + 1) % rim.size()];
            const double profile = frame.underside(p);
            if (!std::isfinite(profile) || !(d_inner + d_outer > 0.0)) continue;
            // A vertex on O itself (where O crossed a fenced edge, at that edge's height) is
            // the terrain the rim follows, which may stand off the chord between rim samples
            // by up to the rim tolerance.
            if (d_outer <= tin.snap_distance()) continue;
            // Where I is enforced next to the vertex, the wall is the new surface: the ramp
            // from I's constrained heights to the rim. Elsewhere nothing re-forms the surface,
            // and only sand above the tool's own wall (its edge at I, sloping to the rim) is
            // pushed down. Taking the lower of the tool and the rim at I everywhere cut a
            // hilltop stamp's untouched sand between the contours, below the tool, by 2 mm.
            const NearestEdge& to_inner = band.to_inner;
            const std::size_t next = (to_inner.index + 1) % inner.size();
            const double inner_end =
                inner_active[to_inner.index]
                    ? (1.0 - to_inner.t) * inner_h[to_inner.index] + to_inner.t * inner_h[next]
                    : profile;
            const double wall = (d_outer * inner_end + d_inner * rim_height) / (d_inner + d_outer);
            if (va.height[v.value] > wall) tin.set_height(v, wall);
        }
        for (VertexId v : band_junk)
            tin.remove_vertex(v, VolumePolicy::Report, &edit);
        // The region's walk also collected the corners of faces reaching into the band.
        if (!band_junk.empty()) {
            std::erase_if(region, [&](VertexId v) { return !tin.is_alive(v); });
            std::erase_if(footprint, [&](VertexId v) { return !tin.is_alive(v); });
        }
    }
    // Vertices a rounding error apart (left where nearly coincident old rims were crossed)
    // can fall on both sides of the contour and get different heights: a vertical sliver.
    // They take the lower height.
    if (dig) equalise_slivers(tin, footprint, true);
    report.displaced_volume = -(tin.volume_ledger() - ledger_start);
    report.enforce_ms = elapsed_ms(t0);

    // 6. Inner vertices that the flat imprint made redundant go at once; the rest of the queue
    //    (released rims, earlier edits) is processed too: this is the end of the iteration.
    //    A flat tool that lowered everything it covers leaves one planar patch: it is removed
    //    in a single step, without testing each vertex (the cost stays near-independent of how
    //    dense the terrain was under the tool).
    const auto t1 = std::chrono::steady_clock::now();
    bool cleared = false;
    if (tool.profile().is_flat() && context.settings.simplify_after_edit && region.size() > 1) {
        bool level = true;
        std::vector<VertexId> interior;
        for (VertexId v : region) {
            if (va.height[v.value] != at.bottom && in_inner.contains(va.position[v.value])) {
                level = false;
                break;
            }
            if (!tin.is_on_constraint(v) && !tin.is_boundary(v) &&
                in_inner.contains(va.position[v.value])) {
                interior.push_back(v);
            }
        }
        if (level && !interior.empty()) {
            EditReport patch;
            cleared = tin.remove_planar_patch(interior, context.settings.simplify.tolerance,
                                              context.settings.simplify.volume_policy, &patch);
            if (cleared) {
                report.simplify.tested += interior.size();
                report.simplify.removed += interior.size();
                report.simplify.volume_change += patch.volume_change;
                report.simplify.max_volume_change = std::abs(patch.volume_change);
            }
        }
    }
    if (!cleared) context.simplifier.enqueue(region);
    // The rest of the footprint too: a vertex of an older rim inside O may have become
    // redundant now that the new contours run next to it (re-working a trail leaves such rims
    // behind on every pass), although its height did not change. Outside O nothing is
    // touched.
    std::erase_if(footprint, [&](VertexId v) { return !tin.is_alive(v); });
    context.simplifier.enqueue(footprint);
    if (context.settings.simplify_after_edit) {
        report.simplify.accumulate(context.simplifier.run(tin, context.settings.simplify));
    }
    report.simplify_ms = elapsed_ms(t1);

    // 7. Extrusion: the displaced volume goes into a ridge ahead of and beside the tool.
    const auto t2 = std::chrono::steady_clock::now();
    // The ridge carries what the tool cut, and the volume re-triangulating around the rim
    // changed, so that the stamp conserves volume exactly: on sand sampled finely beside the
    // tool that is a few per cent of the cut, and no more than a layer far thinner than the
    // tool is wide over its footprint. Delaunay insertion re-triangulates every triangle whose
    // circumcircle holds a rim point: on a coarse, curved TIN (an imported elevation model)
    // that reaches far beyond the tool and changes more volume than a layer as thick as the
    // tool's radius over its footprint. That volume is no sand the tool moved: carried by the
    // ridge, it dug a band 100 m deep beside a 10 cm tool (6.5 m³ re-triangulated, 1.6 l cut,
    // on a 1 m-per-pixel import). It then stays where it happened, reported.
    const double tool_cut = report.displaced_volume + report.retriangulation_volume;
    const double carried =
        std::abs(report.retriangulation_volume) <= std::abs(signed_area(outer)) * tool.radius()
            ? report.retriangulation_volume
            : 0.0;
    const double to_deposit = tool_cut - carried;
    if (tool.spec().extrude && to_deposit != 0.0) {
        // Cut depth at each rim point: that of the nearest inner contour point.
        std::vector<double> cut(rim.size(), 0.0);
        for (std::size_t i = 0; i < rim.size(); ++i) {
            double best = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < inner.size(); ++j) {
                const double d = length_squared(inner[j] - rim[i]);
                if (d < best) {
                    best = d;
                    cut[i] = inner_terrain[j] - inner_h[j];
                }
            }
        }
        std::vector<VertexId> ridge;
        // On a terrain the rim was fenced on, the ridge's band is enclosed too.
        const RidgeFence ridge_fence{tol, generation - 1};
        const RidgeReport ridge_report =
            deposit_ridge(tin, rim, cut, motion, tool.extrusion_width(), to_deposit, hint, &ridge,
                          fenced_terrain ? &ridge_fence : nullptr);
        report.deposited_volume = ridge_report.deposited;
        report.edges_fenced += ridge_report.edges_fenced;
        report.undeposited_volume = to_deposit - ridge_report.deposited;
        context.simplifier.enqueue(ridge);
    }
    report.extrude_ms = elapsed_ms(t2);

    report.volume_change = tin.volume_ledger() - ledger_start;
    report.triangles_touched = edit.triangles_changed;
    report.vertices_inserted = edit.vertices_created;
    report.vertices_removed = edit.vertices_removed + report.simplify.removed;
    return report;
}

}  // namespace sandtin
