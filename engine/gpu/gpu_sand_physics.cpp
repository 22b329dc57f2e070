#include "gpu/gpu_sand_physics.hpp"
#include "util/elapsed_ms.hpp"

#include <algorithm>
#include <chrono>

namespace sandtin::gpu {

namespace {

GpuRelaxationSettings relaxation_settings(const TalusSettings& s, double slide_gain) {
    GpuRelaxationSettings g;
    g.parameters = s.parameters;
    g.quiet_iterations = s.quiet_iterations;
    g.slide_gain = slide_gain;
    g.randomness = s.randomness;
    g.seed = s.seed;
    return g;
}

// The relaxation reads the mirror's buffers from its construction on: the mirror is synced first.
TinMirror& synced(TinMirror& mirror) {
    mirror.sync();
    return mirror;
}

}  // namespace

GpuSandPhysics::GpuSandPhysics(Tin& tin, VulkanContext& context, const MaterialTable& materials,
                               TalusSettings settings, double slide_gain)
    : own_mirror_(std::make_unique<TinMirror>(context, tin, materials)),
      mirror_(*own_mirror_),
      tin_(tin),
      settings_(settings),
      changes_(tin),
      relax_(synced(mirror_), relaxation_settings(settings_, slide_gain)) {}

GpuSandPhysics::GpuSandPhysics(TinMirror& mirror, TalusSettings settings, double slide_gain)
    : mirror_(mirror),
      tin_(mirror.tin()),
      settings_(settings),
      changes_(tin_),
      relax_(synced(mirror_), relaxation_settings(settings_, slide_gain)) {}

GpuSandPhysics::~GpuSandPhysics() = default;

void GpuSandPhysics::set_materials(const MaterialTable& materials) {
    mirror_.set_materials(materials);
    activate_all();
}

void GpuSandPhysics::activate(std::span<const VertexId> vertices) {
    for (VertexId v : vertices)
        if (tin_.is_alive(v)) pending_.push_back(v.value);
}

void GpuSandPhysics::activate_all() {
    const VertexArrays& va = tin_.vertices();
    for (uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) pending_.push_back(v);
}

void GpuSandPhysics::sync() {
    const double gain = relax_.settings().slide_gain;
    relax_.settings() = relaxation_settings(settings_, gain);
    const SyncStats s = mirror_.sync();
    last_sync_bytes_ = s.bytes;
    // Whatever changed on the CPU side since the last step (tools, undo, write-backs,
    // refinement) may now have excess, whoever synced the mirror in between.
    const VertexChanges changed = changes_.take();
    activate(changed.attributes);
    activate(changed.topology);
    relax_.activate(pending_);
    pending_.clear();
}

double GpuSandPhysics::write_back(std::vector<VertexId>* changed) {
    const std::vector<TouchedVertex> touched = relax_.read_back();
    std::vector<VertexId> ids;
    std::vector<double> heights;
    ids.reserve(touched.size());
    heights.reserve(touched.size());
    double moved = 0.0;
    for (const TouchedVertex& t : touched) {
        moved += static_cast<double>(t.moved);
        const VertexId v{t.id};
        // Listed only for what it sent: its height is the TIN's already (writing the float
        // back would round the TIN's double and wake the vertex for nothing).
        if (!t.surface_changed() || !tin_.is_alive(v)) continue;
        ids.push_back(v);
        heights.push_back(static_cast<double>(t.height) + mirror_.height_origin());
        const Vec2f slide{t.slide_x, t.slide_y};
        if (!(tin_.vertices().slide[t.id] == slide)) tin_.set_slide(v, slide);
    }
    tin_.set_heights(ids, heights);
    if (changed != nullptr) changed->insert(changed->end(), ids.begin(), ids.end());
    return moved;
}

std::size_t GpuSandPhysics::refine(std::vector<VertexId>* inserted) {
    const double rs = settings_.parameters.relocation_radius;
    if (!(rs > 0.0)) return 0;
    // The same refinement as SandPhysics (a lattice, bisection where none fits), so the two
    // physics grow the same vertices for the same requests. (It used to split each long edge at
    // r_S from the vertex, an older rule: a pile poured on two triangles grew 696 vertices
    // where the CPU grows 414.)
    std::vector<uint32_t> around = relax_.take_split_requests();
    return refiner_.refine(tin_, around, rs, inserted);
}

PhysicsStepReport GpuSandPhysics::step(int iterations, std::vector<VertexId>* changed) {
    PhysicsStepReport report;
    const auto t0 = std::chrono::steady_clock::now();
    // While the relocation radius refines, shorter batches: refinement runs between batches,
    // and for the rest of a batch the sand waits at the long edges it asked to split. Measured
    // on the CLI dig (8 000 points, r_S = 1 cm, 150 iterations of erosion after a stamp): with
    // 64 iterations per batch the GPU refined 210 vertices and updated 5 017 where the CPU,
    // refining after every iteration, refines 363 and updates 73 419; with 8, 347 and 33 970
    // (with 1, 357 and 37 326, for three times the submissions).
    constexpr int kBatch = 64;
    constexpr int kRefiningBatch = 8;
    int left = iterations;
    while (left > 0) {
        sync();
        if (relax_.at_rest()) break;
        const int n = std::min(left, refining_ ? kRefiningBatch : kBatch);
        const GpuRunStats s = relax_.run(n);
        left -= n;
        report.iterations += s.iterations;
        report.vertex_updates += s.vertex_updates;
        report.changed += s.changed;
        report.volume_moved += write_back(changed);
        const std::size_t refined = refine(changed);
        refining_ = refined > 0;
        report.refined += refined;
    }
    sync();  // refinement and write-backs are on the GPU before the next caller looks
    report.at_rest = at_rest();
    report.ms = elapsed_ms(t0);
    return report;
}

PhysicsStepReport GpuSandPhysics::run_to_rest(int max_iterations, std::vector<VertexId>* changed) {
    PhysicsStepReport total;
    while (total.iterations < max_iterations) {
        const PhysicsStepReport r = step(std::min(256, max_iterations - total.iterations), changed);
        total.accumulate(r);
        if (r.at_rest || r.iterations == 0) break;
    }
    total.at_rest = at_rest();
    return total;
}

}  // namespace sandtin::gpu
