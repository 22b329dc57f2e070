#include "water/moisture_diffusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "geom/vec2.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"
#include "util/compensated_sum.hpp"

namespace sandtin {

namespace {

constexpr std::uint32_t kNotInSet = UINT32_MAX;

/// The share of the vertices (the stiffest) whose own stability bound the sub-step may exceed;
/// their exchanges are slowed to what the sub-step resolves (see the header).
constexpr double kStiffShare = 0.01;
/// The sub-step is never shorter than this share of the median vertex's bound, so that a few
/// slivers among few vertices cannot stall a call.
constexpr double kShortestStepOfMedian = 1.0 / 64.0;

void check_settings(double seconds, const MoistureSettings& s) {
    if (!(seconds >= 0.0) || !std::isfinite(seconds))
        throw std::invalid_argument("moisture: seconds must be a finite number >= 0");
    if (!(s.diffusivity >= 0.0) || !std::isfinite(s.diffusivity))
        throw std::invalid_argument("moisture: diffusivity must be a finite number >= 0 (m²/s)");
    if (!(s.drying_half_life > 0.0))
        throw std::invalid_argument(
            "moisture: drying_half_life must be > 0 (s; infinity: no drying)");
}

/// An edge that exchanges moisture: local indices of its ends and its cotangent weight.
struct Edge {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    double weight = 0.0;
};

/// The vertices the moisture is computed on (wet ones and the neighbours they reached), by
/// local index, with their state in double.
class MoistureSet {
  public:
    explicit MoistureSet(const Tin& tin) : tin_(tin), local_(tin.vertices().size(), kNotInSet) {}

    std::uint32_t add(VertexId v, double moisture) {
        const auto l = static_cast<std::uint32_t>(id_.size());
        local_[v.index()] = l;
        id_.push_back(v);
        area_.push_back(tin_.vertices().lumped_area[v.index()]);
        m_.push_back(moisture);
        weight_sum_.push_back(0.0);
        open_.push_back(0);
        return l;
    }

    /// Takes in the neighbours of every vertex at least kNegligibleMoisture wet that has not
    /// yet, with the edges to them.
    void open_wet_vertices() {
        for (std::uint32_t l = 0; l < id_.size(); ++l) {
            if (!open_[l] && m_[l] >= kNegligibleMoisture) open(l);
        }
    }

    /// The sub-step's bound (s): 0.5 A_i / (D sum_j w_ij) of the vertex at kStiffShare of
    /// the vertices with edges, from the stiffest, but at least kShortestStepOfMedian of the
    /// median one's; +inf with no edge.
    double step_bound(double diffusivity);

    /// One explicit Euler step of spreading: each edge's exchange is worked out once and moves
    /// from one end to the other. A vertex whose own bound is below dt has its exchanges
    /// slowed by bound / dt. Returns how many vertices were slowed.
    std::size_t spread(double diffusivity, double dt);

    /// Exact decay by `factor` over a sub-step. Returns whether any vertex is still at least
    /// kNegligibleMoisture wet.
    bool dry(double factor) {
        bool wet = false;
        for (double& m : m_) {
            m *= factor;
            wet = wet || m >= kNegligibleMoisture;
        }
        return wet;
    }

    std::size_t size() const { return id_.size(); }
    VertexId id(std::size_t l) const { return id_[l]; }
    double moisture(std::size_t l) const { return m_[l]; }
    double area(std::size_t l) const { return area_[l]; }

  private:
    void open(std::uint32_t l);
    /// Cotangent weights of the edges from id_[l] to each of neighbours_ (into weights_).
    void star_weights(VertexId v);

    const Tin& tin_;
    std::vector<std::uint32_t> local_;  ///< by VertexId: its local index, or kNotInSet
    std::vector<VertexId> id_;
    std::vector<double> area_, m_, weight_sum_, delta_, slowing_, ratios_;
    std::vector<std::uint8_t> open_;  ///< its edges are in edges_, its neighbours in the set
    std::vector<Edge> edges_;
    std::size_t edges_seen_ = SIZE_MAX;  ///< edges_.size() when step_bound last looked
    double bound_ratio_ = std::numeric_limits<double>::infinity();  ///< A / sum w it chose
    std::vector<VertexId> neighbours_;
    std::vector<double> weights_;
};

double MoistureSet::step_bound(double diffusivity) {
    if (edges_.size() != edges_seen_) {
        edges_seen_ = edges_.size();
        ratios_.clear();
        for (std::size_t l = 0; l < id_.size(); ++l) {
            if (weight_sum_[l] > 0.0) ratios_.push_back(area_[l] / weight_sum_[l]);
        }
        if (ratios_.empty()) return std::numeric_limits<double>::infinity();
        bound_ratio_ = moisture_step_ratio(ratios_);
    }
    return 0.5 * bound_ratio_ / diffusivity;
}

std::size_t MoistureSet::spread(double diffusivity, double dt) {
    // Slowing s_i = min(1, 0.5 A_i / (D dt sum_j w_ij)); an edge takes the smaller of its
    // ends'. Then m_i keeps at least half its own weight: 1 - D dt sum_j s_ij w_ij / A_i >= 1/2.
    std::size_t slowed = 0;
    slowing_.resize(id_.size());
    for (std::size_t l = 0; l < id_.size(); ++l) {
        const double load = diffusivity * dt * weight_sum_[l];
        slowing_[l] = load > 0.5 * area_[l] ? 0.5 * area_[l] / load : 1.0;
        slowed += slowing_[l] < 1.0 ? 1 : 0;
    }
    delta_.assign(m_.size(), 0.0);
    for (const Edge& e : edges_) {
        const double conductance =
            diffusivity * dt * e.weight * std::min(slowing_[e.a], slowing_[e.b]);
        const double flow = conductance * (m_[e.b] - m_[e.a]);
        delta_[e.a] += flow;
        delta_[e.b] -= flow;
    }
    for (std::size_t l = 0; l < m_.size(); ++l)
        m_[l] += delta_[l] / area_[l];
    return slowed;
}

void MoistureSet::star_weights(VertexId v) {
    // neighbours() lists them counter-clockwise: consecutive ones (a, b) span a triangle
    // (v, a, b) when it turns left. Only the gap of a border vertex does not: 180 degrees on a
    // straight border (orientation exactly 0, the points share a coordinate) and more at a
    // corner.
    tin_.neighbours(v, neighbours_);
    const std::size_t n = neighbours_.size();
    weights_.assign(n, 0.0);
    const Vec2 p = tin_.position(v);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = (k + 1) % n;
        const Vec2 a = tin_.position(neighbours_[k]), b = tin_.position(neighbours_[k1]);
        const double twice_area = cross(a - p, b - p);
        if (!(twice_area > 0.0)) continue;
        // Half the cotangent of the angle at b weighs edge v-a; the angle at a, edge v-b.
        weights_[k] += 0.5 * dot(p - b, a - b) / twice_area;
        weights_[k1] += 0.5 * dot(p - a, b - a) / twice_area;
    }
}

void MoistureSet::open(std::uint32_t l) {
    open_[l] = 1;
    if (!(area_[l] > 0.0)) return;
    star_weights(id_[l]);
    for (std::size_t k = 0; k < neighbours_.size(); ++k) {
        // Clamped at 0: a non-Delaunay edge would carry moisture from the drier end.
        const double w = std::max(weights_[k], 0.0);
        const VertexId j = neighbours_[k];
        if (!(w > 0.0) || !(tin_.vertices().lumped_area[j.index()] > 0.0)) continue;
        std::uint32_t lj = local_[j.index()];
        // Every vertex with moisture joined at the start: one that has not is dry.
        if (lj == kNotInSet) lj = add(j, 0.0);
        // An open neighbour added this edge (from its side) when it opened.
        if (open_[lj]) continue;
        edges_.push_back({l, lj, w});
        weight_sum_[l] += w;
        weight_sum_[lj] += w;
    }
}

/// Writes the changed floats back (with `drying`, moisture below kNegligibleMoisture as 0);
/// fills the report's totals and wettest vertex.
void write_back(Tin& tin, const MoistureSet& set, bool drying, MoistureReport& report) {
    CompensatedSum computed, after;
    for (std::size_t l = 0; l < set.size(); ++l) {
        const VertexId v = set.id(l);
        computed.add(set.area(l) * set.moisture(l));
        // The scheme keeps m in [0, 1]; the clamp only catches rounding at the ends.
        const float m = drying && set.moisture(l) < kNegligibleMoisture
                            ? 0.0f
                            : std::clamp(static_cast<float>(set.moisture(l)), 0.0f, 1.0f);
        if (m != tin.vertices().moisture[v.index()]) {
            tin.set_moisture(v, m);
            ++report.vertices_changed;
        }
        after.add(set.area(l) * static_cast<double>(m));
        if (m > report.wettest_moisture ||
            (m == report.wettest_moisture && m > 0.0f && v < report.wettest)) {
            report.wettest = v;
            report.wettest_moisture = m;
        }
    }
    report.total_computed = computed.value();
    report.total_after = after.value();
}

}  // namespace

double moisture_step_ratio(std::vector<double>& ratios) {
    if (ratios.empty()) return std::numeric_limits<double>::infinity();
    const auto at = [&](double share) {
        const auto k = static_cast<std::ptrdiff_t>(share * static_cast<double>(ratios.size()));
        std::nth_element(ratios.begin(), ratios.begin() + k, ratios.end());
        return ratios[static_cast<std::size_t>(k)];
    };
    const double median = at(0.5);
    return std::max(at(kStiffShare), kShortestStepOfMedian * median);
}

MoistureReport spread_and_dry_moisture(Tin& tin, double seconds, const MoistureSettings& settings) {
    check_settings(seconds, settings);
    MoistureReport report;
    report.seconds = seconds;
    // The read-only pass that finds the wet vertices.
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> wet;
    CompensatedSum before;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v] && va.moisture[v] > 0.0f) {
            wet.push_back(VertexId{static_cast<std::uint32_t>(v)});
            before.add(va.lumped_area[v] * static_cast<double>(va.moisture[v]));
        }
    }
    report.total_before = report.total_after = report.total_computed = before.value();
    const double diffusivity = settings.diffusivity;
    const bool drying = std::isfinite(settings.drying_half_life);
    if (wet.empty() || seconds == 0.0 || (diffusivity == 0.0 && !drying)) {
        // Nothing changes: report the wettest vertex as it is, write nothing.
        for (VertexId v : wet) {
            if (va.moisture[v.index()] > report.wettest_moisture) {
                report.wettest = v;
                report.wettest_moisture = va.moisture[v.index()];
            }
        }
        return report;
    }
    MoistureSet set(tin);
    for (VertexId v : wet)
        set.add(v, va.moisture[v.index()]);
    double remaining = seconds;
    while (remaining > 0.0) {
        if (diffusivity > 0.0) set.open_wet_vertices();
        const double bound = diffusivity > 0.0 ? set.step_bound(diffusivity) : remaining;
        // Equal sub-steps over what is left, as long as the bound holds; the last one takes
        // exactly what is left.
        const double left = std::ceil(remaining / bound);
        const double dt = left <= 1.0 ? remaining : remaining / left;
        if (diffusivity > 0.0)
            report.vertices_slowed = std::max(report.vertices_slowed, set.spread(diffusivity, dt));
        const bool any_wet = !drying || set.dry(std::exp2(-dt / settings.drying_half_life));
        // All below kNegligibleMoisture, and so dry at the end: the time left changes nothing.
        remaining = left <= 1.0 || !any_wet ? 0.0 : remaining - dt;
        ++report.sub_steps;
    }
    report.vertices_computed = set.size();
    write_back(tin, set, drying, report);
    return report;
}

}  // namespace sandtin
