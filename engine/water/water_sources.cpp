#include "water/water_sources.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace sandtin {

namespace {

constexpr double kMmPerHourToMetresPerSecond = 1e-3 / 3600.0;

void check(const WaterSources& s, double dt) {
    const auto rate = [](double r) { return r >= 0.0 && std::isfinite(r); };
    if (!(dt >= 0.0) || !std::isfinite(dt))
        throw std::invalid_argument("water sources: dt must be finite and >= 0");
    for (const Rain& r : s.rain) {
        if (!rate(r.mm_per_hour) || !rate(r.radius) || !std::isfinite(r.centre.x) ||
            !std::isfinite(r.centre.y))
            throw std::invalid_argument(
                "water sources: rain needs a finite rate and radius >= 0 and a finite centre");
    }
    for (const Nozzle& n : s.nozzles) {
        if (!rate(n.litres_per_second) || !std::isfinite(n.at.x) || !std::isfinite(n.at.y))
            throw std::invalid_argument(
                "water sources: a nozzle needs a finite position and a rate >= 0");
        if (!rate(n.radius))
            throw std::invalid_argument("water sources: a nozzle's radius must be finite and >= 0");
    }
    if (!rate(s.evaporation_mm_per_hour))
        throw std::invalid_argument("water sources: evaporation must be finite and >= 0");
}

/// The vertex with area nearest to p (the vertex count when none holds water).
std::size_t nearest_wet_capable(const WaterMesh& m, Vec2 p) {
    std::size_t best = m.area.size();
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t v = 0; v < m.area.size(); ++v) {
        if (!(m.area[v] > 0.0)) continue;
        const double d2 = dot(m.position[v] - p, m.position[v] - p);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = v;
        }
    }
    return best;
}

}  // namespace

template <class Water>
SourceReport apply_sources(Water& water, const WaterSources& sources, double dt) {
    check(sources, dt);
    const WaterMesh& m = water.mesh();
    SourceReport report;
    for (const Rain& r : sources.rain) {
        const double rise = r.mm_per_hour * kMmPerHourToMetresPerSecond * dt;
        if (!(rise > 0.0)) continue;
        for (std::size_t v = 0; v < m.area.size(); ++v) {
            if (!(m.area[v] > 0.0)) continue;
            if (r.radius > 0.0 && length(m.position[v] - r.centre) > r.radius) continue;
            if constexpr (std::is_same_v<Water, ShallowWater>) {
                water.add_water(v, m.area[v] * rise);  // no momentum of its own
            } else {
                water.set_depth(v, water.depth(v) + rise);
            }
            report.added += m.area[v] * rise;
        }
    }
    std::vector<std::size_t> under_jet;
    for (const Nozzle& n : sources.nozzles) {
        const double volume = n.litres_per_second * 1e-3 * dt;
        if (!(volume > 0.0)) continue;
        under_jet.clear();
        double jet_area = 0.0;
        if (n.radius > 0.0) {
            for (std::size_t v = 0; v < m.area.size(); ++v) {
                if (!(m.area[v] > 0.0) || length(m.position[v] - n.at) > n.radius) continue;
                under_jet.push_back(v);
                jet_area += m.area[v];
            }
        }
        if (under_jet.empty()) {
            const std::size_t v = nearest_wet_capable(m, n.at);
            if (v == m.area.size()) continue;
            water.add_water(v, volume);
            report.added += volume;
            continue;
        }
        const double rise = volume / jet_area;
        for (const std::size_t v : under_jet) {
            water.add_water(v, m.area[v] * rise);
            report.added += m.area[v] * rise;
        }
    }
    const double fall = sources.evaporation_mm_per_hour * kMmPerHourToMetresPerSecond * dt;
    if (fall > 0.0) {
        for (std::size_t v = 0; v < m.area.size(); ++v) {
            const double gone = std::min(water.depth(v), fall);
            if (!(gone > 0.0)) continue;
            water.set_depth(v, gone == water.depth(v) ? 0.0 : water.depth(v) - gone);
            report.evaporated += m.area[v] * gone;
        }
    }
    return report;
}

template SourceReport apply_sources(VirtualPipes&, const WaterSources&, double);
template SourceReport apply_sources(ShallowWater&, const WaterSources&, double);

}  // namespace sandtin
