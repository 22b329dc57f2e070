#include "physics/sand_physics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "util/elapsed_ms.hpp"
#include "util/prepare_for_writing.hpp"

namespace sandtin {

SandPhysics::SandPhysics(Tin& tin, MaterialTable materials, TalusSettings settings,
                         VertexOrder order)
    : tin_(tin),
      materials_(std::move(materials)),
      solver_(settings),
      order_(order != VertexOrder::Auto              ? order
             : settings.schedule == Schedule::Jacobi ? VertexOrder::Strips
                                                     : VertexOrder::Tin),
      changes_(tin) {
    const VertexArrays& va = tin_.vertices();
    material_seen_.assign(va.material.begin(), va.material.end());
    moisture_seen_.assign(va.moisture.begin(), va.moisture.end());
    if (order_ == VertexOrder::Strips) {
        numbering_.assign_strips(tin_);
    } else {
        numbering_.assign_identity(tin_);
    }
    graph_.rebuild(tin_, &numbering_);
    grow_local();
    prepare_work_arrays();
}

void SandPhysics::prepare_work_arrays() {
    solver_.prepare(graph_, height_.size());
    active_.reserve_ids(height_.size());
    if (write_pending_.size() < height_.size()) write_pending_.resize(height_.size(), 0);
}

void SandPhysics::load(std::uint32_t l) {
    const VertexArrays& va = tin_.vertices();
    const std::uint32_t t = numbering_.tin_id(l);
    const bool alive = t < va.size() && va.alive[t];
    height_[l] = alive ? va.height[t] : 0.0;
    tan_alpha_[l] = alive ? materials_.at(va.material[t]).talus_slope(va.moisture[t]) : 0.0;
    if (!numbering_.identity()) {
        area_[l] = alive ? va.lumped_area[t] : 0.0;
        bedrock_[l] = alive ? va.bedrock[t] : 0.0;
    }
}

void SandPhysics::grow_local() {
    const std::uint32_t n = numbering_.size();
    const auto old = static_cast<std::uint32_t>(height_.size());
    if (n <= old) return;
    reserve_for_writing(height_, n);
    reserve_for_writing(tan_alpha_, n);
    height_.resize(n);
    tan_alpha_.resize(n);
    if (!numbering_.identity()) {
        reserve_for_writing(area_, n);
        reserve_for_writing(bedrock_, n);
        area_.resize(n);
        bedrock_.resize(n);
    }
    for (std::uint32_t l = old; l < n; ++l)
        load(l);
}

TalusArrays SandPhysics::arrays() {
    const VertexArrays& va = tin_.vertices();
    if (numbering_.identity())
        return {height_.data(),    va.lumped_area.data(), va.bedrock.data(),
                tan_alpha_.data(), height_.size(),        nullptr};
    return {height_.data(),    area_.data(),   bedrock_.data(),
            tan_alpha_.data(), height_.size(), numbering_.tin_ids().data()};
}

void SandPhysics::number(std::span<const VertexId> vertices) {
    const VertexArrays& va = tin_.vertices();
    bool added = false;
    for (VertexId v : vertices) {
        if (v.value < va.size() && va.alive[v.value] &&
            numbering_.local(v.value) == VertexNumbering::kNone) {
            numbering_.add(v.value);
            added = true;
        }
    }
    if (added) grow_local();
}

void SandPhysics::apply_topology(std::span<const VertexId> topology) {
    if (topology.empty()) return;
    number(topology);
    graph_.update(tin_, topology, &numbering_);
}

bool SandPhysics::is_active(VertexId v) const {
    const std::uint32_t l = numbering_.local(v.value);
    return l != VertexNumbering::kNone && active_.contains(l);
}

void SandPhysics::renumber() {
    // Only sync() renumbers, and every sync() in a step follows a flush(): nothing is pending.
    if (!write_local_.empty()) throw std::logic_error("sand physics: renumbering with writes");
    const VertexNumbering old = numbering_;
    numbering_.assign_strips(tin_);
    const std::uint32_t n = numbering_.size();
    std::vector<std::uint32_t> new_id(old.size());
    for (std::uint32_t l = 0; l < old.size(); ++l)
        new_id[l] = numbering_.local(old.tin_id(l));
    // Heights and slopes move with their vertices (height_ may hold what the TIN has not been
    // given yet); area and bedrock are reloaded from the TIN.
    std::vector<double> height(n), tan_alpha(n);
    for (std::uint32_t l = 0; l < old.size(); ++l) {
        if (new_id[l] == VertexNumbering::kNone) continue;
        height[new_id[l]] = height_[l];
        tan_alpha[new_id[l]] = tan_alpha_[l];
    }
    height_ = std::move(height);
    tan_alpha_ = std::move(tan_alpha);
    area_.resize(n);
    bedrock_.resize(n);
    const VertexArrays& va = tin_.vertices();
    for (std::uint32_t l = 0; l < n; ++l) {
        area_[l] = va.lumped_area[numbering_.tin_id(l)];
        bedrock_[l] = va.bedrock[numbering_.tin_id(l)];
    }
    active_.renumber(new_id, VertexNumbering::kNone);
    graph_.rebuild(tin_, &numbering_);
    prepare_work_arrays();
    ++renumberings_;
}

SandPhysics::~SandPhysics() = default;

void SandPhysics::set_materials(const MaterialTable& materials) {
    materials_ = materials;
    // tan_alpha_ is per local id: under a renumbering (Jacobi's strips) local l is TIN id
    // numbering_.tin_id(l), not l.
    const VertexArrays& va = tin_.vertices();
    for (std::uint32_t l = 0; l < numbering_.size() && l < tan_alpha_.size(); ++l) {
        const std::uint32_t t = numbering_.tin_id(l);
        if (t < va.size() && va.alive[t])
            tan_alpha_[l] = materials_.at(va.material[t]).talus_slope(va.moisture[t]);
    }
    activate_all();
}

void SandPhysics::activate(std::span<const VertexId> vertices) {
    number(vertices);
    for (VertexId v : vertices) {
        if (tin_.is_alive(v)) active_.activate(numbering_.local(v.value));
    }
}

void SandPhysics::activate_all() {
    const VertexArrays& va = tin_.vertices();
    std::vector<VertexId> live;
    live.reserve(tin_.vertex_count());
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) live.push_back(VertexId{v});
    }
    number(live);
    for (VertexId v : live)
        active_.activate(numbering_.local(v.value));
}

void SandPhysics::sync() {
    const VertexChanges changes = changes_.take();
    const VertexArrays& va = tin_.vertices();
    if (material_seen_.size() < va.size()) {
        material_seen_.resize(va.size(), 0xFFFF);
        moisture_seen_.resize(va.size(), -1.0f);
    }
    apply_topology(changes.topology);
    const bool copies = !numbering_.identity();
    std::vector<std::uint32_t> died;     // local ids, leaving the active set in one batch
    std::vector<std::uint32_t> touched;  // local ids of live changed vertices
    auto refresh = [&](VertexId v) {
        const std::uint32_t l = numbering_.local(v.value);
        if (!va.alive[v.value]) {
            if (l != VertexNumbering::kNone) died.push_back(l);
            return;
        }
        height_[l] = va.height[v.value];
        if (copies) {
            area_[l] = va.lumped_area[v.value];  // changes with the star: in `topology`
            bedrock_[l] = va.bedrock[v.value];
        }
        // tan(repose) only when the material or moisture changed: heights change far more often.
        if (material_seen_[v.value] != va.material[v.value] ||
            moisture_seen_[v.value] != va.moisture[v.value]) {
            material_seen_[v.value] = va.material[v.value];
            moisture_seen_[v.value] = va.moisture[v.value];
            tan_alpha_[l] = materials_.at(va.material[v.value]).talus_slope(va.moisture[v.value]);
        }
        active_.activate(l);
        touched.push_back(l);
    };
    // A vertex whose attributes changed without its star is numbered already, unless it was
    // born before the last sync and never seen: number() covers that.
    number(changes.attributes);
    for (VertexId v : changes.attributes)
        refresh(v);
    for (VertexId v : changes.topology)
        refresh(v);
    // And their neighbours (as the GPU's activation does): a vertex an edit lowered, or whose
    // height a simplification shifted, steepens the edges from the neighbours above it, and only
    // those neighbours send sand down them. Measured: after the erode tests' groove stroke,
    // "until rest" stopped with edges still 4 % steeper than repose, which a physics with every
    // vertex active then levelled in 3 iterations. A vertex in both lists is listed twice here;
    // activating it again changes nothing.
    const std::uint32_t* target = graph_.targets().data();
    for (std::uint32_t l : touched) {
        const std::uint32_t row = graph_.offsets()[l];
        for (std::uint32_t k = row; k < row + graph_.degree(l); ++k)
            active_.activate(target[k]);
    }
    active_.remove(died);
    if (copies &&
        numbering_.appended() >= std::max<std::size_t>(kRenumberMinimum, numbering_.size() / 4))
        renumber();
}

std::size_t SandPhysics::refine(std::vector<std::uint32_t>& around,
                                std::vector<VertexId>* inserted) {
    return refiner_.refine(tin_, around, solver_.settings().parameters.relocation_radius, inserted);
}

std::size_t SandPhysics::refine_around(std::span<const VertexId> vertices) {
    if (!(solver_.settings().parameters.relocation_radius > 0.0)) return 0;
    const double rs = solver_.settings().parameters.relocation_radius;
    std::size_t inserted = 0;
    // Bisection halves the longest edges each round, so this takes log2(longest / r_S) rounds.
    for (;;) {
        sync();
        std::vector<std::uint32_t> around;
        for (VertexId v : vertices) {
            if (tin_.is_alive(v) &&
                graph_.longest_edge(numbering_.local(v.value)) > rs * (1.0 + 1e-9))
                around.push_back(v.value);
        }
        const std::size_t added = refine(around);
        inserted += added;
        if (added == 0) break;
    }
    sync();
    return inserted;
}

void SandPhysics::flush(std::vector<VertexId>* changed_out) {
    if (write_local_.empty()) return;
    write_ids_.clear();
    write_values_.clear();
    for (std::uint32_t l : write_local_) {
        write_ids_.push_back(VertexId{numbering_.tin_id(l)});
        write_values_.push_back(height_[l]);
        write_pending_[l] = 0;
    }
    write_local_.clear();
    tin_.set_heights(write_ids_, write_values_);
    if (changed_out != nullptr)
        changed_out->insert(changed_out->end(), write_ids_.begin(), write_ids_.end());
    const VertexChanges echo = changes_.take();
    // set_heights changes attributes only; anything else would be an edit we must not drop.
    apply_topology(echo.topology);
}

PhysicsStepReport SandPhysics::step(int iterations, std::vector<VertexId>* changed_out) {
    PhysicsStepReport report;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> split_local, split_around;
    // Heights stay in height_ for the whole step: writing them into the TIN every iteration and
    // reading them back through the change journal cost about 12 % of the step (a 60 000-vertex
    // dig eroded to rest, Jacobi). They go into the TIN at the end and before refinement, which
    // interpolates the TIN's heights.
    sync();
    for (int it = 0; it < iterations; ++it) {
        if (active_.empty()) break;
        if (write_pending_.size() < height_.size()) write_pending_.resize(height_.size(), 0);
        const IterationStats stats = solver_.iterate(graph_, arrays(), active_, &split_local);
        ++report.iterations;
        report.vertex_updates += stats.processed;
        report.changed += stats.changed;
        report.volume_moved += stats.volume_moved;
        for (std::uint32_t l : solver_.changed()) {
            if (!write_pending_[l]) {
                write_pending_[l] = 1;
                write_local_.push_back(l);
            }
        }
        if (!split_local.empty()) {
            split_around.clear();
            for (std::uint32_t l : split_local)
                split_around.push_back(numbering_.tin_id(l));
            split_local.clear();
            // Jacobi reports them in the order of its (local) ids; refinement depends on the
            // order, so it gets them in TIN-id order, whatever the numbering. The sequential
            // schedule's order is its visiting order, the same in every numbering.
            if (solver_.settings().schedule == Schedule::Jacobi) {
                std::sort(split_around.begin(), split_around.end());
                split_around.erase(std::unique(split_around.begin(), split_around.end()),
                                   split_around.end());
            }
            flush(changed_out);
            report.refined += refine(split_around, changed_out);
            sync();
        }
    }
    flush(changed_out);
    sync();
    report.at_rest = active_.empty();
    report.ms = elapsed_ms(t0);
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
