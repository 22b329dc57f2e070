#include "water/sediment_transport.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace sandtin {

namespace {

std::span<const VirtualPipes::Pipe> edges_of(const VirtualPipes& w) {
    return w.pipes();
}
std::span<const ShallowWater::Interface> edges_of(const ShallowWater& w) {
    return w.interfaces();
}

}  // namespace

SedimentTransport::SedimentTransport(const WaterMesh& m, std::vector<double> bedrock,
                                     SedimentOptions options, std::vector<std::uint16_t> material)
    : bedrock_(std::move(bedrock)), options_(options) {
    if (material.empty()) material.assign(m.bed.size(), 0);
    if (material.size() != m.bed.size())
        throw std::invalid_argument("sediment: material must have one entry per vertex");
    palette_ = material;
    std::sort(palette_.begin(), palette_.end());
    palette_.erase(std::unique(palette_.begin(), palette_.end()), palette_.end());
    bed_kind_.resize(material.size());
    for (std::size_t v = 0; v < material.size(); ++v) {
        bed_kind_[v] = static_cast<std::uint16_t>(
            std::lower_bound(palette_.begin(), palette_.end(), material[v]) - palette_.begin());
    }
    held_by_kind_.assign(material.size() * palette_.size(), 0.0);
    dropped_by_kind_.assign(material.size() * palette_.size(), 0.0);
    change_by_kind_.assign(material.size() * palette_.size(), 0.0);
    if (bedrock_.size() != m.bed.size())
        throw std::invalid_argument("sediment: bedrock must have one entry per vertex");
    for (std::size_t v = 0; v < bedrock_.size(); ++v) {
        if (std::isnan(bedrock_[v]) || bedrock_[v] > m.bed[v])
            throw std::invalid_argument("sediment: the bedrock at vertex " + std::to_string(v) +
                                        " is not a number or lies above the bed");
    }
    const auto rate = [](double r) { return r >= 0.0 && std::isfinite(r); };
    if (!rate(options_.capacity) || !rate(options_.pick_up_rate) || !rate(options_.drop_rate) ||
        !rate(options_.least_slope) || !rate(options_.max_concentration) ||
        options_.max_concentration > 1.0)
        throw std::invalid_argument(
            "sediment: every constant must be finite and >= 0, max_concentration at most 1");
    held_.assign(bedrock_.size(), 0.0);
}

void SedimentTransport::move_suspension(std::size_t v, double share, double* into) {
    const std::size_t kinds = palette_.size();
    for (std::size_t k = 0; k < kinds; ++k) {
        const double part = share * held_by_kind_[v * kinds + k];
        into[k] += part;
        change_by_kind_[v * kinds + k] -= part;
    }
}

std::size_t SedimentTransport::top_kind(std::size_t v) const {
    const std::size_t kinds = palette_.size();
    std::size_t best = bed_kind_[v];
    for (std::size_t k = 0; k < kinds; ++k) {
        if (dropped_by_kind_[v * kinds + k] > dropped_by_kind_[v * kinds + best]) best = k;
    }
    return best;
}

void SedimentTransport::apply_changes() {
    for (std::size_t i = 0; i < held_by_kind_.size(); ++i) {
        held_by_kind_[i] = std::max(0.0, held_by_kind_[i] + change_by_kind_[i]);
        change_by_kind_[i] = 0.0;
    }
}

double SedimentTransport::dropped(std::size_t v) const {
    const std::size_t kinds = palette_.size();
    double sum = 0.0;
    for (std::size_t k = 0; k < kinds; ++k)
        sum += dropped_by_kind_[v * kinds + k];
    return sum;
}

std::uint16_t SedimentTransport::deposited_material(std::size_t v) const {
    return palette_[top_kind(v)];
}

double SedimentTransport::suspended() const {
    double sum = 0.0;
    for (double h : held_)
        sum += h;
    return sum;
}

template <class Water>
void SedimentTransport::step(Water& water, double dt) {
    const WaterMesh& m = water.mesh();
    const std::size_t n = held_.size();
    // Phase 1: each vertex's flow speed and steepest bed slope, from its pipes.
    std::vector<double> discharge(n, 0.0), slope(n, 0.0);
    for (const auto& p : edges_of(water)) {
        discharge[p.a] += 0.5 * std::abs(p.flux);
        discharge[p.b] += 0.5 * std::abs(p.flux);
        const double s =
            std::abs(m.bed[p.a] - m.bed[p.b]) / length(m.position[p.a] - m.position[p.b]);
        slope[p.a] = std::max(slope[p.a], s);
        slope[p.b] = std::max(slope[p.b], s);
    }
    // Phase 2: pick up or drop towards the capacity.
    for (std::size_t v = 0; v < n; ++v) {
        const double area = m.area[v], depth = water.depth(v);
        if (!(area > 0.0)) continue;
        double speed = pipe_flow_speed(discharge[v], depth, area);
        if constexpr (std::is_same_v<Water, ShallowWater>) speed = length(water.velocity(v));
        const double capacity =
            std::min(options_.capacity * speed * std::max(slope[v], options_.least_slope) * area,
                     options_.max_concentration * depth * area);
        double bed = m.bed[v];
        if (held_[v] < capacity) {
            const double sand = std::max(0.0, bed - bedrock_[v]) * area;
            const double taken = std::min(options_.pick_up_rate * (capacity - held_[v]) * dt, sand);
            held_[v] += taken;
            // Of the material on top: what was dropped there most, else the bed's own.
            held_by_kind_[v * palette_.size() + top_kind(v)] += taken;
            bed = taken == sand ? std::max(bedrock_[v], bed - taken / area) : bed - taken / area;
        } else if (held_[v] > 0.0) {
            const double dropped =
                std::min(options_.drop_rate * (held_[v] - capacity) * dt, held_[v]);
            if (held_[v] > 0.0)
                move_suspension(v, dropped / held_[v], &dropped_by_kind_[v * palette_.size()]);
            held_[v] -= dropped;
            bed += dropped / area;
        }
        if (bed != m.bed[v]) water.set_bed(v, bed);
    }
    apply_changes();  // what was dropped leaves the suspension's materials before it moves
    // Phase 3: the suspended sand moves with the water, at the upwind vertex's concentration
    // (suspended m³ per m³ of water), each vertex giving at most what it holds.
    std::vector<double> out(n, 0.0);
    for (const auto& p : edges_of(water)) {
        if (p.flux == 0.0) continue;
        const std::uint32_t from = p.flux > 0.0 ? p.a : p.b;
        const double water_there = water.depth(from) * m.area[from];
        if (water_there > 0.0) out[from] += std::abs(p.flux) * dt * held_[from] / water_there;
    }
    std::vector<double> scale(n, 1.0), change(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (out[v] > held_[v]) scale[v] = held_[v] / out[v];
    }
    for (const auto& p : edges_of(water)) {
        if (p.flux == 0.0) continue;
        const std::uint32_t from = p.flux > 0.0 ? p.a : p.b, to = from == p.a ? p.b : p.a;
        const double water_there = water.depth(from) * m.area[from];
        if (!(water_there > 0.0)) continue;
        const double moved = std::abs(p.flux) * dt * held_[from] / water_there * scale[from];
        change[from] -= moved;
        change[to] += moved;
        if (held_[from] > 0.0)
            move_suspension(from, moved / held_[from], &change_by_kind_[to * palette_.size()]);
    }
    for (std::size_t v = 0; v < n; ++v)
        held_[v] = std::max(0.0, held_[v] + change[v]);
    apply_changes();
}

template <class Water>
void SedimentTransport::settle_all(Water& water) {
    const WaterMesh& m = water.mesh();
    for (std::size_t v = 0; v < held_.size(); ++v) {
        if (!(held_[v] > 0.0) || !(m.area[v] > 0.0)) continue;
        water.set_bed(v, m.bed[v] + held_[v] / m.area[v]);
        move_suspension(v, 1.0, &dropped_by_kind_[v * palette_.size()]);
        held_[v] = 0.0;
    }
    apply_changes();
}

template void SedimentTransport::step(VirtualPipes&, double);
template void SedimentTransport::step(ShallowWater&, double);
template void SedimentTransport::settle_all(VirtualPipes&);
template void SedimentTransport::settle_all(ShallowWater&);

}  // namespace sandtin
