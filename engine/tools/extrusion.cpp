#include "tools/extrusion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geom/near_edge_index.hpp"
#include "geom/point_grid.hpp"
#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "tools/slivers.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {

namespace {

/// Stations along the contour's normals make sure a sparse terrain has vertices to carry the
/// ridge; they are inserted on the surface, so they change nothing yet. A line of them every
/// quarter width of contour (their spacing across the band: the contour's own points can be
/// much closer), only at contour points of positive weight, and a station only where no vertex
/// is within an eighth of the width already: along a stroke the previous stamps' stations are
/// there, and a dense terrain needs none. Otherwise every stamp would add hundreds of vertices
/// for the simplifier to take out again. The stations join `band`.
void insert_stations(Tin& tin, std::span<const Vec2> outer, std::span<const Vec2> normal,
                     std::span<const double> weight, double width, std::vector<VertexId>& band,
                     LocateHint* hint) {
    const double line_spacing = 0.25 * width;
    const double clearance = 0.125 * width;
    static constexpr std::array<double, 4> kStations = {0.25, 0.5, 0.75, 1.0};
    const VertexArrays& va = tin.vertices();
    std::vector<Vec2> band_positions;
    band_positions.reserve(band.size());
    for (VertexId v : band)
        band_positions.push_back(va.position[v.value]);
    const PointGrid existing(band_positions, clearance);
    const Rect domain = tin.domain();
    std::vector<Vec2> points;
    double since_line = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < outer.size(); ++i) {
        if (i > 0) since_line += distance(outer[i], outer[i - 1]);
        if (!(weight[i] > 0.0) || since_line < line_spacing) continue;
        since_line = 0.0;
        for (double s : kStations) {
            const Vec2 p = outer[i] + normal[i] * (s * width);
            if (domain.contains(p) && !point_in_polygon(p, outer) && !existing.has_near(p))
                points.push_back(p);
        }
    }
    if (points.empty()) return;
    const std::vector<VertexId> stations =
        tin.insert_points_on_surface(points, hint, VolumePolicy::Conserve);
    band.insert(band.end(), stations.begin(), stations.end());
    // A station may land on an existing vertex (within the snap distance).
    std::sort(band.begin(), band.end());
    band.erase(std::unique(band.begin(), band.end()), band.end());
}

/// The cut depth along the closed contour, piecewise linear between its points, averaged over
/// `half_window` metres of contour either side of each point. A ridge as wide as the band
/// cannot follow a cut that changes from one contour point to the next: weighted point by
/// point, the shipped foot (its toes, and each outline point its profile missed) heaped the
/// sand in radial stripes, each the width of one rim edge and the band's length.
std::vector<double> smoothed_along(std::span<const Vec2> contour, std::span<const double> cut,
                                   double half_window) {
    const std::size_t n = contour.size();
    // Arc length at each point, and the integral of the cut from point 0 to each point.
    std::vector<double> at(n + 1, 0.0);
    std::vector<double> integral(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
        const double len = distance(contour[k], contour[(k + 1) % n]);
        at[k + 1] = at[k] + len;
        integral[k + 1] = integral[k] + 0.5 * len * (cut[k] + cut[(k + 1) % n]);
    }
    const double perimeter = at[n];
    if (!(perimeter > 0.0) || !(half_window > 0.0)) return {cut.begin(), cut.end()};
    if (2.0 * half_window >= perimeter) return std::vector<double>(n, integral[n] / perimeter);
    // The integral of the cut from point 0 to arc length s, for any s (the contour repeats).
    auto integral_to = [&](double s) {
        const double turns = std::floor(s / perimeter);
        const double x = s - turns * perimeter;
        const auto k = static_cast<std::size_t>(
            std::clamp<std::ptrdiff_t>(std::upper_bound(at.begin(), at.end(), x) - at.begin() - 1,
                                       0, static_cast<std::ptrdiff_t>(n) - 1));
        const double len = at[k + 1] - at[k];
        const double t = len > 0.0 ? std::clamp((x - at[k]) / len, 0.0, 1.0) : 0.0;
        const double c0 = cut[k];
        const double ct = c0 + t * (cut[(k + 1) % n] - c0);
        return turns * integral[n] + integral[k] + 0.5 * t * len * (c0 + ct);
    };
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i)
        out[i] = (integral_to(at[i] + half_window) - integral_to(at[i] - half_window)) /
                 (2.0 * half_window);
    return out;
}

/// Each band vertex's share k_v of the ridge, in id order: at distance s outside O (within the
/// width w), the cross-section 1 - (2s/w - 1)² times the weight interpolated along the nearest
/// contour edge. Every vertex in the band carries the ridge, not only the stations: on a dense
/// terrain the stations are a small share of the band's vertices, and raising them alone would
/// hold the volume in needles (a 5 mm-spaced terrain once grew 4 cm spikes that way).
std::vector<std::pair<VertexId, double>> ridge_shares(const Tin& tin,
                                                      std::span<const VertexId> band,
                                                      std::span<const double> weight,
                                                      const PolygonInclusion& under_tool,
                                                      const NearEdgeIndex& rim, double width) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = weight.size();
    std::vector<std::pair<VertexId, double>> ks;
    for (VertexId v : band) {
        if (!tin.is_alive(v)) continue;
        const Vec2 p = va.position[v.value];
        if (under_tool.contains(p)) continue;
        const NearestEdge edge = rim.nearest_within_reach(p);
        const double w =
            (1.0 - edge.t) * weight[edge.index] + edge.t * weight[(edge.index + 1) % n];
        if (!(edge.distance < width) || !(w > 0.0)) continue;
        const double t = 2.0 * edge.distance / width - 1.0;
        const double kv = w * (1.0 - t * t);
        if (kv > 0.0) ks.emplace_back(v, kv);
    }
    std::sort(ks.begin(), ks.end());  // deterministic order
    return ks;
}

/// The band's outer edge on a coarse TIN (RidgeFence): the contour offset by the width, clipped
/// to the domain, points a quarter width apart, inserted at the surface's height and
/// constrained once the bent edges around it are fenced.
void enclose_band(Tin& tin, std::span<const Vec2> outer, double width, const RidgeFence& fence,
                  LocateHint* hint, RidgeReport& report) {
    const Rect domain = tin.domain();
    std::vector<Vec2> edge = clip_to_rect(offset_contour(outer, width), domain.min, domain.max);
    if (edge.size() < 3) return;
    edge = subdivide_contour(edge, 0.25 * width);
    std::vector<std::array<Vec2, 2>> sides;
    for (std::size_t k = 0; k < edge.size(); ++k)
        sides.push_back({edge[k], edge[(k + 1) % edge.size()]});
    report.edges_fenced +=
        tin.fence_bent_edges(edge, sides, fence.tolerance, fence.generation, nullptr, hint);
    const std::vector<VertexId> ids =
        tin.insert_points_on_surface(edge, hint, VolumePolicy::Report);
    std::vector<std::array<VertexId, 2>> segments;
    for (std::size_t k = 0; k < ids.size(); ++k) {
        const VertexId a = ids[k];
        const VertexId b = ids[(k + 1) % ids.size()];
        // Along the domain's border the hull holds the band already.
        if (a != b && !domain.has_on_one_side(tin.position(a), tin.position(b)))
            segments.push_back({a, b});
    }
    tin.insert_constraints(segments, fence.generation, VolumePolicy::Report);
}

}  // namespace

RidgeReport deposit_ridge(Tin& tin, std::span<const Vec2> outer, std::span<const double> cut_depth,
                          std::optional<Vec2> motion, double width, double volume, LocateHint* hint,
                          std::vector<VertexId>* touched, const RidgeFence* fence) {
    RidgeReport report;
    const std::size_t n = outer.size();
    if (volume == 0.0 || !std::isfinite(volume) || n < 3 || !(width > 0.0)) return report;

    // Per-vertex weights: cut depth (averaged along the contour over a quarter of the width
    // either side) times the direction factor.
    std::vector<double> cut(n);
    for (std::size_t i = 0; i < n; ++i)
        cut[i] = std::max(0.0, cut_depth[i]);
    cut = smoothed_along(outer, cut, 0.25 * width);
    std::vector<double> cut_weight(n, 0.0);
    std::vector<Vec2> normal(n);
    double total_weight = 0.0;
    std::vector<double> direction(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 prev = outer[(i + n - 1) % n];
        const Vec2 next = outer[(i + 1) % n];
        const Vec2 e1 = (outer[i] - prev) / std::max(length(outer[i] - prev), 1e-300);
        const Vec2 e2 = (next - outer[i]) / std::max(length(next - outer[i]), 1e-300);
        Vec2 nrm = Vec2{e1.y, -e1.x} + Vec2{e2.y, -e2.x};
        nrm = nrm / std::max(length(nrm), 1e-300);
        normal[i] = nrm;
        if (motion && length(*motion) > 0.0) {
            const Vec2 d = *motion / length(*motion);
            direction[i] = std::clamp((dot(nrm, d) + 0.5) / 1.5, 0.0, 1.0);
        }
        cut_weight[i] = cut[i] * direction[i];
        total_weight += cut_weight[i];
    }
    // Weights in order of preference. The tool may displace volume where no control point
    // reports a cut (a ball's outline stands above the sand), and the weighted part of the
    // band may lie outside the domain (a tool in a corner, moving into it): then the
    // direction alone, then every side alike, rather than lose the volume.
    std::vector<std::vector<double>> preferences;
    if (total_weight > 0.0) preferences.push_back(cut_weight);
    preferences.push_back(direction);
    const std::vector<double> every_side(n, 1.0);
    if (direction != every_side) preferences.push_back(every_side);  // no motion: the same

    // Enclosing the band re-triangulates what its fences leave free (edges bent by less than
    // their tolerance): the ridge makes up that volume, so the deposit is exact.
    const double ledger_start = tin.volume_ledger();
    if (fence != nullptr) enclose_band(tin, outer, width, *fence, hint, report);
    const double to_raise = volume - (tin.volume_ledger() - ledger_start);

    // The band's vertices: every vertex within reach of the ridge, before any is added.
    Rect box;
    for (Vec2 p : outer)
        box.expand(p);
    const Vec2 centre = (box.min + box.max) * 0.5;
    double reach = 0.0;
    for (Vec2 p : outer)
        reach = std::max(reach, distance(p, centre));
    std::vector<VertexId> band = tin.vertices_in_disc(centre, reach + width, hint);
    const VertexArrays& va = tin.vertices();

    // A dense terrain has thousands of vertices under and around the tool, and its rim
    // hundreds of edges: both tests are indexed (same answers as point_in_polygon and
    // nearest_edge).
    const PolygonInclusion under_tool(outer, centre);
    const NearEdgeIndex rim(outer, width);
    const std::size_t before = tin.vertex_count();
    std::vector<std::pair<VertexId, double>> ks;
    double denominator = 0.0;
    for (const std::vector<double>& weight : preferences) {
        insert_stations(tin, outer, normal, weight, width, band, hint);
        ks = ridge_shares(tin, band, weight, under_tool, rim, width);
        denominator = 0.0;
        for (const auto& [v, kv] : ks)
            denominator += va.lumped_area[v.value] * kv;
        if (denominator > 0.0) break;
    }
    report.vertices_inserted = tin.vertex_count() - before;
    if (!(denominator > 0.0)) {
        report.deposited = tin.volume_ledger() - ledger_start;
        return report;
    }
    const double ridge_height = to_raise / denominator;
    for (const auto& [v, kv] : ks) {
        tin.set_height(v, va.height[v.value] + ridge_height * kv);
        if (touched != nullptr) touched->push_back(v);
    }
    std::vector<VertexId> raised;
    for (const auto& [v, kv] : ks)
        raised.push_back(v);
    equalise_slivers(tin, raised, volume < 0.0);
    report.deposited = tin.volume_ledger() - ledger_start;
    return report;
}

}  // namespace sandtin
