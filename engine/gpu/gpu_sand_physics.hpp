#pragma once
// Sand physics with the relaxation on the GPU: the same interface as physics/SandPhysics
// (step, run_to_rest, settings, activate), so a caller picks CPU or GPU at run time
// (`--physics cpu|gpu`) and gets the same terrain within float tolerance.
//
// Each step: the TinMirror uploads what changed in the TIN since the last step (those vertices
// become active), the GPU runs the iterations, and the vertices whose height or texture-slide
// offset changed are read back into the TIN (set_heights / set_slide), so exports, saves and
// haptic snapshots always see the current terrain. Edges longer than the relocation radius are
// split on the CPU between GPU submissions (as SandPhysics does between iterations).
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
#include "tin/tin.hpp"

namespace sandtin::gpu {

class VulkanContext;

class GpuSandPhysics {
  public:
    // Where the mirror's syncs get the TIN's changes. Empty: tin.take_changes() (this object
    // is the journal's only consumer). A caller that shares the journal with other consumers
    // (the editor's render mesh) passes a source that hands every consumer the same changes.
    using ChangeSource = std::function<ChangeSet()>;

    // The TIN must track changes (TinOptions::track_changes) and outlive the physics; this
    // object becomes the consumer of Tin::take_changes() (or of `source`).
    GpuSandPhysics(Tin& tin, VulkanContext& context, MaterialTable materials,
                   TalusSettings settings = {}, double slide_gain = 0.0, ChangeSource source = {});

    TalusSettings& settings() { return settings_; }
    void activate(std::span<const VertexId> vertices);
    void activate_all();
    // New angles of repose: every live vertex's tan(alpha) is re-uploaded at the next step and
    // every vertex becomes active.
    void set_materials(MaterialTable materials);
    bool at_rest() const { return relax_.at_rest() && pending_.empty(); }
    std::size_t active_count() const { return relax_.active_count() + pending_.size(); }

    // As SandPhysics::step / run_to_rest. Iterations run on the GPU in batches of up to 64
    // per submission (8 while r_S refines); a batch that starts at rest records nothing.
    PhysicsStepReport step(int iterations = 1, std::vector<VertexId>* changed = nullptr);
    PhysicsStepReport run_to_rest(int max_iterations, std::vector<VertexId>* changed = nullptr);

    TinMirror& mirror() { return mirror_; }
    GpuRelaxation& relaxation() { return relax_; }
    uint64_t last_sync_bytes() const { return last_sync_bytes_; }

  private:
    void sync();
    ChangeSet take_changes();
    /// Reads back what the GPU changed into the TIN (appending the vertices to `changed`) and
    /// returns the volume the vertices sent since the last read-back (m³).
    double write_back(std::vector<VertexId>* changed);
    // Refines where the relaxation asked (RelocationRefiner); appends what it inserted.
    std::size_t refine(std::vector<VertexId>* inserted);
    bool refining_ = false;  ///< the last batch refined: the next one is short (step())

    Tin& tin_;
    TalusSettings settings_;
    ChangeSource source_;
    TinMirror mirror_;
    GpuRelaxation relax_;
    RelocationRefiner refiner_;
    std::vector<uint32_t> pending_;
    uint64_t last_sync_bytes_ = 0;
};

}  // namespace sandtin::gpu
