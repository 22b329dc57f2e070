#include "physics/sand_physics.hpp"

#include <algorithm>
#include <chrono>

namespace sandtin {

void PhysicsStepReport::accumulate(const PhysicsStepReport& o) {
    iterations += o.iterations;
    vertex_updates += o.vertex_updates;
    changed += o.changed;
    refined += o.refined;
    volume_moved += o.volume_moved;
    ms += o.ms;
    at_rest = o.at_rest;
}

SandPhysics::SandPhysics(Tin& tin, MaterialTable materials, TalusSettings settings)
    : tin_(tin), materials_(std::move(materials)), solver_(settings) {
    subscription_ = tin_.subscribe_vertex_changes();
    graph_.rebuild(tin_);
    const VertexArrays& va = tin_.vertices();
    height_.assign(va.height.begin(), va.height.end());
    tan_alpha_.resize(va.size());
    material_seen_.assign(va.material.begin(), va.material.end());
    moisture_seen_.assign(va.moisture.begin(), va.moisture.end());
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) tan_alpha_[v] = materials_.at(va.material[v]).talus_slope(va.moisture[v]);
    }
}

SandPhysics::~SandPhysics() {
    tin_.unsubscribe_vertex_changes(subscription_);
}

void SandPhysics::set_materials(MaterialTable materials) {
    materials_ = std::move(materials);
    const VertexArrays& va = tin_.vertices();
    for (std::size_t v = 0; v < va.size() && v < tan_alpha_.size(); ++v) {
        if (va.alive[v]) tan_alpha_[v] = materials_.at(va.material[v]).talus_slope(va.moisture[v]);
    }
    activate_all();
}

void SandPhysics::activate(std::span<const VertexId> vertices) {
    for (VertexId v : vertices) {
        if (tin_.is_alive(v)) active_.activate(v.value);
    }
}

void SandPhysics::activate_all() {
    const VertexArrays& va = tin_.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) active_.activate(v);
    }
}

void SandPhysics::sync() {
    const VertexChanges changes = tin_.take_vertex_changes(subscription_);
    const VertexArrays& va = tin_.vertices();
    if (height_.size() < va.size()) {
        height_.resize(va.size(), 0.0);
        tan_alpha_.resize(va.size(), 0.0);
        material_seen_.resize(va.size(), 0xFFFF);
        moisture_seen_.resize(va.size(), -1.0f);
    }
    if (!changes.topology.empty()) graph_.update(tin_, changes.topology);
    auto refresh = [&](VertexId v) {
        if (!va.alive[v.value]) {
            active_.remove(v.value);
            return;
        }
        height_[v.value] = va.height[v.value];
        // tan(repose) only when the material or moisture changed: heights change far more often.
        if (material_seen_[v.value] != va.material[v.value] ||
            moisture_seen_[v.value] != va.moisture[v.value]) {
            material_seen_[v.value] = va.material[v.value];
            moisture_seen_[v.value] = va.moisture[v.value];
            tan_alpha_[v.value] =
                materials_.at(va.material[v.value]).talus_slope(va.moisture[v.value]);
        }
        active_.activate(v.value);
    };
    for (VertexId v : changes.attributes)
        refresh(v);
    for (VertexId v : changes.topology)
        refresh(v);
}

std::size_t SandPhysics::refine(std::vector<std::uint32_t>& around) {
    if (around.empty()) return 0;
    const double rs = solver_.settings().parameters.relocation_radius;
    const VertexArrays& va = tin_.vertices();
    if (split_requested_.size() < va.size()) split_requested_.resize(va.size(), 0);
    std::vector<EdgeSplit> splits;
    for (std::uint32_t v : around) {
        if (split_requested_[v] || !va.alive[v]) continue;
        split_requested_[v] = 1;
        const std::uint32_t begin = graph_.offset(v);
        for (std::uint32_t k = begin; k < begin + graph_.degree(v); ++k) {
            const double len = graph_.lengths()[k];
            if (!(len > rs * (1.0 + 1e-9))) continue;
            // On the circle of radius r_S around v (seed 000 §7.2), or halfway when the edge
            // is shorter than 2 r_S, so no piece stays longer than r_S and no new vertex lands
            // next to an old one.
            splits.push_back(
                {VertexId{v}, VertexId{graph_.targets()[k]}, std::min(rs, 0.5 * len) / len});
        }
    }
    for (std::uint32_t v : around)
        split_requested_[v] = 0;
    around.clear();
    if (splits.empty()) return 0;
    const std::size_t before = tin_.vertex_count();
    tin_.split_edges(splits, VolumePolicy::Conserve);
    return tin_.vertex_count() - before;
}

PhysicsStepReport SandPhysics::step(int iterations, std::vector<VertexId>* changed_out) {
    PhysicsStepReport report;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> split_around;
    for (int it = 0; it < iterations; ++it) {
        sync();
        if (active_.empty()) break;
        const VertexArrays& va = tin_.vertices();
        const TalusArrays arrays{height_.data(), va.lumped_area.data(), va.bedrock.data(),
                                 tan_alpha_.data(), va.size()};
        const IterationStats stats = solver_.iterate(graph_, arrays, active_, &split_around);
        ++report.iterations;
        report.vertex_updates += stats.processed;
        report.changed += stats.changed;
        report.volume_moved += stats.volume_moved;
        const std::vector<std::uint32_t>& changed = solver_.changed();
        if (!changed.empty()) {
            write_ids_.clear();
            write_values_.clear();
            for (std::uint32_t v : changed) {
                write_ids_.push_back(VertexId{v});
                write_values_.push_back(height_[v]);
            }
            tin_.set_heights(write_ids_, write_values_);
            if (changed_out != nullptr)
                changed_out->insert(changed_out->end(), write_ids_.begin(), write_ids_.end());
        }
        report.refined += refine(split_around);
    }
    sync();
    report.at_rest = active_.empty();
    report.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

PhysicsStepReport SandPhysics::run_to_rest(int max_iterations, std::vector<VertexId>* changed) {
    PhysicsStepReport total;
    constexpr int kChunk = 64;
    while (total.iterations < max_iterations) {
        const PhysicsStepReport r =
            step(std::min(kChunk, max_iterations - total.iterations), changed);
        total.accumulate(r);
        if (r.at_rest || r.iterations == 0) break;
    }
    total.at_rest = active_.empty();
    return total;
}

}  // namespace sandtin
