// A stamp's contours before anything changes: where they lie, the terrain along them, and which
// of their segments the stamp needs to enforce (phases 1 and 2 of tools/stamp.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "tools/detail/stamp_phases.hpp"
#include "tools/imprint_activity.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin::detail {

namespace {

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

/// Douglas-Peucker on one edge's section of `count` samples (position `t(k)` along the edge,
/// height `h(k)`): marks in `keep` the samples that the chord between kept samples misses by
/// more than `tolerance`, none closer than `min_dt` (in t) to a kept one. Only samples for which
/// `candidate(k)` holds may be kept. `stack` is scratch.
template <class Position, class Height, class Candidate>
void keep_by_douglas_peucker(std::size_t count, Position t, Height h, Candidate candidate,
                             double tolerance, double min_dt, std::vector<std::uint8_t>& keep,
                             std::vector<std::pair<std::size_t, std::size_t>>& stack) {
    stack.assign(1, {0, count - 1});
    while (!stack.empty()) {
        const auto [lo, hi] = stack.back();
        stack.pop_back();
        double worst = 0.0;
        std::size_t at = lo;
        for (std::size_t k = lo + 1; k < hi; ++k) {
            if (!candidate(k)) continue;
            const double f = (t(k) - t(lo)) / (t(hi) - t(lo));
            const double chord = (1.0 - f) * h(lo) + f * h(hi);
            const double dev = std::abs(h(k) - chord);
            if (dev > worst) {
                worst = dev;
                at = k;
            }
        }
        // A point closer than min_dt to a kept one would only make sliver triangles (tiny
        // vertices slow the relaxation down to their own scale).
        if (worst > tolerance && t(at) - t(lo) > min_dt && t(hi) - t(at) > min_dt) {
            keep[at] = 1;
            stack.emplace_back(lo, at);
            stack.emplace_back(at, hi);
        }
    }
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
        keep_by_douglas_peucker(
            sec.size(), [&](std::size_t k) { return sec[k].first; },
            [&](std::size_t k) { return sec[k].second; }, [](std::size_t) { return true; },
            tolerance, min_dt, keep, stack);
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
        keep_by_douglas_peucker(
            samples.size(), [&](std::size_t k) { return samples[k].t; },
            [&](std::size_t k) { return samples[k].height; },
            [&](std::size_t k) { return samples[k].clear; }, tolerance, min_dt, keep, stack);
        for (std::size_t k = 1; k + 1 < samples.size(); ++k) {
            if (keep[k]) out.push_back(lerp(a, b, samples[k].t));
        }
    }
    return out;
}

/// A curved profile's interior samples, with the underside's height and the terrain's at each,
/// for the draped inner contour `inner`.
ProfileLattice sample_lattice(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                              const ToolFrame& frame, std::span<const Vec2> inner,
                              bool inner_clipped, LocateHint* hint) {
    ProfileLattice lattice;
    const Tool::InteriorSamples& samples = tool.interior_samples();
    if (inner_clipped) {
        // Part of I lies outside the domain: a lattice of the clipped contour. (The tool's
        // own lattice with the samples past the border left out leaves a wider strip
        // unsampled there: the ball then missed its imprint by 1.2 mm 2 mm from the
        // border, against the 1 mm its test allows.)
        lattice.points = interior_lattice(inner, samples.spacing);
        // The lattice keeps half a spacing from every edge, the stretch along the domain's
        // border too, where the profile does not drop to the rim as it does along the
        // tool's outline: samples on that stretch as well, one spacing apart. (Without
        // them the border between I's two corners there only interpolated those corners:
        // a ball or foot pressed at the border of a terrain with no vertices along it
        // missed its imprint by up to 14 mm on the border line.)
        const std::vector<Vec2> along_border =
            samples_along_sides(inner, tin.domain(), samples.spacing);
        lattice.points.insert(lattice.points.end(), along_border.begin(), along_border.end());
        for (Vec2 p : lattice.points)
            lattice.underside.push_back(frame.underside(p));
    } else {
        lattice.points.reserve(samples.local.size());
        for (Vec2 p : samples.local)
            lattice.points.push_back(frame.to_world(p));
        for (double offset : samples.offset)
            lattice.underside.push_back(at.bottom + offset);
    }
    lattice.terrain.resize(lattice.points.size());
    tin.heights_at(lattice.points, lattice.terrain, hint);
    for (double& h : lattice.terrain) {
        if (std::isnan(h)) h = 0.0;  // outside the domain, as surface_or
    }
    return lattice;
}

/// The rim segments next to an active segment of I: within the contours' gap and one rim
/// spacing of it.
std::vector<std::uint8_t> rim_next_to_active_inner(const Tool& tool, const ContourSamples& s,
                                                   const std::vector<std::uint8_t>& inner_active) {
    const std::vector<Vec2>& rim = s.rim;
    const std::vector<Vec2>& inner = s.inner;
    std::vector<std::uint8_t> rim_active(rim.size(), 0);
    const double reach = tool.shape().gap + tool.rim_spacing();
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
    return rim_active;
}

/// Marks the rim segments an older constraint crosses: the release splits that constraint where
/// O crosses it, and a constrained O keeps the release's flips from reaching the older imprint
/// outside.
void activate_rim_crossing_older(const Tin& tin, const std::vector<Vec2>& rim,
                                 Generation generation, std::vector<std::uint8_t>& rim_active) {
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
}

}  // namespace

std::optional<PlacedContours> place_contours(const Tin& tin, const Tool& tool,
                                             const ToolFrame& frame) {
    const Rect domain = tin.domain();
    const double spacing = tool.rim_spacing();
    const double eps = 1e-9 * std::max(tool.radius(), 1e-9);
    auto to_world = [&](std::span<const Vec2> local) {
        std::vector<Vec2> out;
        for (Vec2 p : subdivide_contour(local, spacing))
            out.push_back(frame.to_world(p));
        return out;
    };
    PlacedContours c;
    c.outer = drop_near_duplicates(
        clip_to_rect(to_world(tool.shape().outer), domain.min, domain.max), eps);
    const std::vector<Vec2> inner_whole = to_world(tool.shape().inner);
    c.inner_clipped = !std::all_of(inner_whole.begin(), inner_whole.end(),
                                   [&](Vec2 p) { return domain.contains(p); });
    c.inner = drop_near_duplicates(clip_to_rect(inner_whole, domain.min, domain.max), eps);
    if (c.outer.size() < 3 || c.inner.size() < 3 || !(std::abs(signed_area(c.inner)) > eps * eps)) {
        return std::nullopt;
    }
    return c;
}

ContourSamples sample_contours(const Tin& tin, const Tool& tool, const ToolPlacement& at,
                               const PlacedContours& contours, const Imprint& imprint,
                               double simplify_tolerance, LocateHint* hint) {
    ContourSamples s;
    const double min_spacing = 0.25 * tool.shape().gap;
    // I follows the sand the tool stands above to the coarser of the rim's tolerance and the
    // simplifier's: a floor the simplifier's volume-conserving shifts left a hair below the
    // tool (re-working a trail) is no sand to follow, and chasing it at the rim's 1 % of a small
    // tool's radius made a 10^5-stamp stroke's vertices grow without end.
    s.inner = drape_inner(tin, contours.inner, imprint.frame(), imprint.dig(),
                          std::max(tool.rim_tolerance(), simplify_tolerance), min_spacing, hint);
    sample_rim(tin, contours.outer, tool.rim_tolerance(), min_spacing, hint, s.rim, s.rim_h,
               s.rim_crossings);
    s.inner_terrain.resize(s.inner.size());
    for (std::size_t i = 0; i < s.inner.size(); ++i)
        s.inner_terrain[i] = surface_or(tin, s.inner[i], hint, 0.0);
    if (!tool.profile().is_flat()) {
        s.lattice =
            sample_lattice(tin, tool, at, imprint.frame(), s.inner, contours.inner_clipped, hint);
    }
    s.inner_h.resize(s.inner.size());
    for (std::size_t i = 0; i < s.inner.size(); ++i)
        s.inner_h[i] = imprint(s.inner[i], s.inner_terrain[i]);
    return s;
}

std::optional<ActiveSegments> find_active_segments(const Tin& tin, const Tool& tool, Vec2 centre,
                                                   const ContourSamples& samples,
                                                   const Imprint& imprint, double tolerance,
                                                   Generation generation, LocateHint* hint) {
    // An inner segment is active where the terrain along it (pre-stamp) stands off the tool by
    // more than the tolerance (imprint_activity.hpp); an outer segment is kept next to an
    // active inner one. Along the trail of a stroke the trailing half of each contour lies in
    // sand already dug to the tool's depth, and constraining it would only create vertices the
    // next stamp removes again.
    const double lateral = tool.shape().gap;
    const ImprintActivity activity =
        inner_contour_activity(tin, samples.inner, imprint, tolerance, lateral, hint);
    bool acts = activity.any_segment;
    // A curved profile also acts inside I: its interior samples decide too.
    const ProfileLattice& lattice = samples.lattice;
    for (std::size_t k = 0; k < lattice.points.size() && !acts; ++k)
        acts = std::abs(lattice.terrain[k] -
                        imprint.under(lattice.underside[k], lattice.terrain[k])) > tolerance;
    if (!acts && !interior_stands_off(tin, samples.inner, imprint, tolerance, lateral, centre,
                                      tool.shape().bounding_radius, hint)) {
        return std::nullopt;
    }
    ActiveSegments active;
    active.inner = activity.inner_active;
    // A tool that cuts only inside I (a wide tool pressed into a hilltop) still needs its
    // footprint: without its contours, the triangles from the lowered sand inside I reached
    // past O and tilted the surface there (1.9 mm, 7.7 cm beyond O). Its I and O are
    // enforced whole, I at the sand's own height where the tool stands above it.
    if (!activity.any_segment) std::fill(active.inner.begin(), active.inner.end(), 1);
    active.rim = rim_next_to_active_inner(tool, samples, active.inner);
    activate_rim_crossing_older(tin, samples.rim, generation, active.rim);
    return active;
}

}  // namespace sandtin::detail
