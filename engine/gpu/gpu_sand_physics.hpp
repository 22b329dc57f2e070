#pragma once
// Sand physics with the relaxation on the GPU: a RelaxationSolver (physics/terrain_solver.hpp)
// like physics/SandPhysics, so a caller picks CPU or GPU at run time (`--physics cpu|gpu`) and
// gets the same terrain within float tolerance.
//
// Each step: the TinMirror uploads what changed in the TIN since its last sync, the physics'
// vertex feed activates what changed since its last step, the GPU runs the iterations, and the
// vertices whose height or texture-slide offset changed are read back into the TIN (set_heights /
// set_slide), so exports, saves and haptic snapshots always see the current terrain. Edges longer
// than the relocation radius are split on the CPU between GPU submissions (as SandPhysics does
// between iterations).
//
// Differences from the CPU physics: the schedule is always Jacobi (TalusSettings::schedule and
// threads are ignored), and volume_moved is summed in float per vertex between read-backs.

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "gpu/gpu_relaxation.hpp"
#include "gpu/tin_mirror.hpp"
#include "physics/material.hpp"
#include "physics/relocation_refinement.hpp"
#include "physics/sand_physics.hpp"
#include "physics/terrain_solver.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_change_feed.hpp"

namespace sandtin::gpu {

class VulkanContext;

class GpuSandPhysics final : public RelaxationSolver {
  public:
    // Relaxes `tin` through a mirror of its own. The TIN must outlive the physics.
    GpuSandPhysics(Tin& tin, VulkanContext& context, const MaterialTable& materials,
                   TalusSettings settings = {}, double slide_gain = 0.0);
    // Relaxes the TIN of a mirror someone else owns and also reads (the editor's terrain view
    // bakes its normal map from it), so the TIN is on the GPU once. The mirror must outlive
    // the physics; the physics sets its materials.
    explicit GpuSandPhysics(TinMirror& mirror, TalusSettings settings = {},
                            double slide_gain = 0.0);
    ~GpuSandPhysics() override;
    GpuSandPhysics(const GpuSandPhysics&) = delete;
    GpuSandPhysics& operator=(const GpuSandPhysics&) = delete;

    SolverDevice device() const override { return SolverDevice::Gpu; }
    // Float heights on the GPU: each erosion drifts by rounding, which the ledger shows.
    bool conserves_volume_exactly() const override { return false; }
    TalusSettings& settings() override { return settings_; }
    void activate(std::span<const VertexId> vertices) override;
    void activate_all() override;
    // New angles of repose: every live vertex's tan(alpha) is re-uploaded at the next step and
    // every vertex becomes active.
    void set_materials(const MaterialTable& materials) override;
    bool at_rest() const override { return relax_.at_rest() && pending_.empty(); }
    std::size_t active_count() const override { return relax_.active_count() + pending_.size(); }

    // As SandPhysics::step / run_to_rest. Iterations run on the GPU in batches of up to 64
    // per submission (8 while r_S refines); a batch that starts at rest records nothing.
    PhysicsStepReport step(int iterations = 1, std::vector<VertexId>* changed = nullptr) override;
    PhysicsStepReport run_to_rest(int max_iterations,
                                  std::vector<VertexId>* changed = nullptr) override;
    std::uint64_t device_dispatches() const override { return relax_.dispatches_recorded(); }

    TinMirror& mirror() { return mirror_; }
    GpuRelaxation& relaxation() { return relax_; }
    uint64_t last_sync_bytes() const { return last_sync_bytes_; }

  private:
    // Brings the mirror up to the TIN and activates what changed there since the last step
    // (tools, undo, write-backs, refinement), from the physics' own vertex feed.
    void sync();
    /// Reads back what the GPU changed into the TIN (appending the vertices to `changed`) and
    /// returns the volume the vertices sent since the last read-back (m³).
    double write_back(std::vector<VertexId>* changed);
    // Refines where the relaxation asked (RelocationRefiner); appends what it inserted.
    std::size_t refine(std::vector<VertexId>* inserted);
    bool refining_ = false;  ///< the last batch refined: the next one is short (step())

    std::unique_ptr<TinMirror> own_mirror_;  // null when the mirror is borrowed
    TinMirror& mirror_;
    Tin& tin_;
    TalusSettings settings_;
    VertexChangeFeed changes_;
    GpuRelaxation relax_;
    RelocationRefiner refiner_;
    std::vector<uint32_t> pending_;
    uint64_t last_sync_bytes_ = 0;
};

}  // namespace sandtin::gpu
