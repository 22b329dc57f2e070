#include "physics/curvature_weathering.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "physics/mean_curvature.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {

WeatheringReport& WeatheringReport::operator+=(const WeatheringReport& r) {
    vertices_worn += r.vertices_worn;
    vertices_raised += r.vertices_raised;
    volume_moved += r.volume_moved;
    deepest_wear = std::max(deepest_wear, r.deepest_wear);
    mean_edge = r.mean_edge;
    largest_curvature = std::max(largest_curvature, r.largest_curvature);
    return *this;
}

namespace {

/// |H| e_avg below this is rounding on a plane, not a bend (a plane's Laplacian is exactly
/// tangential; its normal part is a few ulps of the edge lengths).
constexpr double kRoundingBend = 1e-9;

Vec3 point_of(const VertexArrays& va, VertexId v) {
    const Vec2 p = va.position[v.value];
    return {p.x, p.y, va.height[v.value]};
}

/// Phase 1: each set vertex's neighbours, counter-clockwise, in one flat array.
struct Stars {
    std::vector<VertexId> centre;        ///< live set vertices
    std::vector<double> weight;          ///< per centre
    std::vector<std::size_t> first;      ///< per centre, into ring; one past the end last
    std::vector<VertexId> ring;          ///< neighbours of all centres
    std::vector<std::uint8_t> interior;  ///< per centre: a closed star
};

Stars gather_stars(const Tin& tin, std::span<const VertexId> vertices,
                   std::span<const double> weight) {
    Stars s;
    std::vector<VertexId> ring;
    s.first.push_back(0);
    for (std::size_t k = 0; k < vertices.size(); ++k) {
        if (!tin.is_alive(vertices[k])) continue;
        const Tin::VertexStar star = tin.star(vertices[k], ring);
        s.centre.push_back(vertices[k]);
        s.weight.push_back(weight.empty() ? 1.0 : weight[k]);
        s.interior.push_back(star.boundary ? 0 : 1);
        s.ring.insert(s.ring.end(), ring.begin(), ring.end());
        s.first.push_back(s.ring.size());
    }
    return s;
}

/// Phase 2: the mean curvature of each closed star, and the set's mean edge length.
std::vector<double> star_curvatures(const VertexArrays& va, const Stars& s, double& mean_edge) {
    std::vector<double> h(s.centre.size(), 0.0);
    std::vector<Vec3> ring;
    double edge_sum = 0.0;
    std::size_t edges = 0;
    for (std::size_t k = 0; k < s.centre.size(); ++k) {
        const Vec3 c = point_of(va, s.centre[k]);
        ring.clear();
        for (std::size_t r = s.first[k]; r < s.first[k + 1]; ++r) {
            ring.push_back(point_of(va, s.ring[r]));
            edge_sum += length(ring.back() - c);
            ++edges;
        }
        if (s.interior[k]) h[k] = mean_curvature_of_star(c, ring);
    }
    mean_edge = edges > 0 ? edge_sum / static_cast<double>(edges) : 0.0;
    return h;
}

/// The set's normalised curvature c, looked up by vertex id (0 for vertices outside it).
class CurvatureLookup {
  public:
    CurvatureLookup(const Stars& s, const std::vector<double>& c) {
        by_id_.reserve(s.centre.size());
        for (std::size_t k = 0; k < s.centre.size(); ++k)
            by_id_.emplace_back(s.centre[k].value, c[k]);
        std::sort(by_id_.begin(), by_id_.end());
    }
    double operator()(VertexId v) const {
        const auto it = std::lower_bound(
            by_id_.begin(), by_id_.end(),
            std::pair<std::uint32_t, double>{v.value, -std::numeric_limits<double>::infinity()});
        return it != by_id_.end() && it->first == v.value ? it->second : 0.0;
    }

  private:
    std::vector<std::pair<std::uint32_t, double>> by_id_;
};

struct HeightChange {
    std::uint32_t id;
    double dz;
};

/// Phase 3: vertex k's wear (step 3 and the limits) and its shares to its lower neighbours,
/// appended to `changes`. Returns the wear d (0 when it keeps its sand).
double wear_one(const VertexArrays& va, const Stars& s, std::size_t k, double c,
                const CurvatureLookup& curvature, const WeatheringSettings& settings,
                double mean_edge, std::vector<double>& share, std::vector<HeightChange>& changes) {
    const std::uint32_t i = s.centre[k].value;
    const double h = va.height[i];
    double d = s.weight[k] * settings.strength * std::pow(c, settings.power) * mean_edge / 10.0;
    d = std::min(d, h - va.bedrock[i]);
    if (!(d > 0.0)) return 0.0;
    share.clear();
    double total = 0.0;
    for (std::size_t r = s.first[k]; r < s.first[k + 1]; ++r) {
        const VertexId j = s.ring[r];
        const double drop = h - va.height[j.value];
        const double w = drop > 0.0 ? drop * (1.0 + std::max(0.0, -curvature(j))) : 0.0;
        share.push_back(w);
        total += w;
    }
    if (!(total > 0.0)) return 0.0;
    // Keep h_i - d >= h_j + rise_j + (the other half of the drop): no slope inverts, even
    // with other donors feeding j in the same iteration.
    const double area = va.lumped_area[i];
    for (std::size_t r = s.first[k]; r < s.first[k + 1]; ++r) {
        const double w = share[r - s.first[k]];
        if (!(w > 0.0)) continue;
        const std::uint32_t j = s.ring[r].value;
        const double rise_per_d = area * w / (va.lumped_area[j] * total);
        d = std::min(d, 0.5 * (h - va.height[j]) / (1.0 + rise_per_d));
    }
    if (!(d > 0.0)) return 0.0;
    changes.push_back({i, -d});
    const double volume = area * d;
    for (std::size_t r = s.first[k]; r < s.first[k + 1]; ++r) {
        const double w = share[r - s.first[k]];
        if (!(w > 0.0)) continue;
        const std::uint32_t j = s.ring[r].value;
        changes.push_back({j, volume * (w / total) / va.lumped_area[j]});
    }
    return d;
}

void check(const WeatheringSettings& settings) {
    if (!(settings.strength >= 0.0 && settings.strength <= 1.0))
        throw std::invalid_argument("weathering: strength must lie in [0, 1]");
    if (!(settings.power >= 1.0) || !std::isfinite(settings.power))
        throw std::invalid_argument("weathering: power must be a finite number >= 1");
}

}  // namespace

WeatheringReport weather_vertices(Tin& tin, std::span<const VertexId> vertices,
                                  std::span<const double> weight,
                                  const WeatheringSettings& settings) {
    check(settings);
    if (!weight.empty() && weight.size() != vertices.size())
        throw std::invalid_argument("weathering: one weight per vertex, or none");
    for (double w : weight) {
        if (!(w >= 0.0 && w <= 1.0))
            throw std::invalid_argument("weathering: weights must lie in [0, 1]");
    }
    WeatheringReport report;
    const VertexArrays& va = tin.vertices();
    const Stars stars = gather_stars(tin, vertices, weight);
    const std::vector<double> h = star_curvatures(va, stars, report.mean_edge);
    for (double x : h)
        report.largest_curvature = std::max(report.largest_curvature, std::abs(x));
    if (!(report.mean_edge > 0.0)) return report;
    if (report.largest_curvature * report.mean_edge < kRoundingBend) return report;

    const double normaliser = std::max(report.largest_curvature, kNearlyFlat / report.mean_edge);
    std::vector<double> c(h.size());
    for (std::size_t k = 0; k < h.size(); ++k)
        c[k] = std::abs(h[k]) * report.mean_edge < kRoundingBend ? 0.0 : h[k] / normaliser;
    const CurvatureLookup curvature(stars, c);

    std::vector<HeightChange> changes;
    std::vector<double> share;
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (!(c[k] > 0.0) || !(stars.weight[k] > 0.0)) continue;
        const double d =
            wear_one(va, stars, k, c[k], curvature, settings, report.mean_edge, share, changes);
        if (d > 0.0) {
            ++report.vertices_worn;
            report.deepest_wear = std::max(report.deepest_wear, d);
            report.volume_moved += va.lumped_area[stars.centre[k].value] * d;
        }
    }
    if (changes.empty()) return report;

    // Phase 4: sum each vertex's changes in one order (by id, then as made) and write them.
    std::stable_sort(changes.begin(), changes.end(),
                     [](const HeightChange& a, const HeightChange& b) { return a.id < b.id; });
    std::vector<VertexId> ids;
    std::vector<double> heights;
    for (std::size_t k = 0; k < changes.size();) {
        const std::uint32_t id = changes[k].id;
        double dz = 0.0;
        bool raised = false;
        for (; k < changes.size() && changes[k].id == id; ++k) {
            dz += changes[k].dz;
            raised = raised || changes[k].dz > 0.0;
        }
        if (raised) ++report.vertices_raised;
        ids.push_back(VertexId{id});
        heights.push_back(va.height[id] + dz);
    }
    tin.set_heights(ids, heights);
    return report;
}

WeatheringReport weather_terrain(Tin& tin, int iterations, const WeatheringSettings& settings) {
    check(settings);
    if (iterations < 0) throw std::invalid_argument("weathering: iterations must be >= 0");
    WeatheringReport report;
    std::vector<VertexId> all;
    for (int it = 0; it < iterations; ++it) {
        all.clear();
        const VertexArrays& va = tin.vertices();
        for (std::size_t v = 0; v < va.size(); ++v) {
            if (va.alive[v]) all.push_back(VertexId{static_cast<std::uint32_t>(v)});
        }
        const WeatheringReport r = weather_vertices(tin, all, {}, settings);
        report += r;
        if (r.vertices_worn == 0) break;
    }
    return report;
}

}  // namespace sandtin
