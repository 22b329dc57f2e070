#pragma once
// The physics seam: one interface for every process that moves material over the TIN, whatever
// runs it. The CPU relaxation (SandPhysics) and the GPU relaxation (gpu::GpuSandPhysics)
// implement RelaxationSolver; a water solver implements TerrainSolver. The editor's frame loop
// and the script runner step a solver without knowing which it is or where it runs.
//
// Contract shared by every solver:
//   - it follows the TIN's changes itself (a vertex feed of its own, tin/vertex_change_feed.hpp):
//     whatever a tool, a brush or an undo changes becomes active at its next step, and nobody
//     has to tell it;
//   - step() writes its results into the TIN before it returns (heights, texture slide), so
//     saves, exports, the render mesh and the haptic snapshots see the current terrain;
//   - an idle solver costs nothing: at_rest() is true and step() does no work.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/material.hpp"
#include "physics/physics_step_report.hpp"
#include "physics/talus_solver.hpp"
#include "tin/ids.hpp"

namespace sandtin {

/// Where a solver's iterations run.
enum class SolverDevice : std::uint8_t { Cpu, Gpu };

/// "cpu" or "gpu".
const char* to_string(SolverDevice device);

class TerrainSolver {
  public:
    virtual ~TerrainSolver() = default;

    virtual SolverDevice device() const = 0;
    /// New materials (angles of repose, erodibility): every vertex is looked at again.
    virtual void set_materials(const MaterialTable& materials) = 0;
    /// Makes these vertices candidates for the next step (beyond what the TIN's changes wake).
    virtual void activate(std::span<const VertexId> vertices) = 0;
    /// Every live vertex becomes a candidate (e.g. a loaded terrain that is not at rest).
    virtual void activate_all() = 0;
    virtual bool at_rest() const = 0;
    /// Vertices still being worked on.
    virtual std::size_t active_count() const = 0;
    /// Up to `iterations` iterations (fewer at rest). The vertices whose height changed, and
    /// the vertices the solver inserted, are appended to `changed` when given.
    virtual PhysicsStepReport step(int iterations, std::vector<VertexId>* changed = nullptr) = 0;
    /// Iterates until at rest or `max_iterations` ran.
    virtual PhysicsStepReport run_to_rest(int max_iterations,
                                          std::vector<VertexId>* changed = nullptr) = 0;
    /// True when the solver conserves volume to double rounding, so its volume change is 0;
    /// false for float arithmetic (the GPU), whose drift the TIN's volume ledger shows.
    virtual bool conserves_volume_exactly() const = 0;
    /// Device dispatches recorded so far (0 on the CPU): an idle terrain must add none.
    virtual std::uint64_t device_dispatches() const { return 0; }
};

/// A solver of the critical-slope relaxation (seed 000 §7, seed 003 §3.2): sand above its
/// angle of repose slides to its neighbours until every slope is at most tan α.
class RelaxationSolver : public TerrainSolver {
  public:
    virtual TalusSettings& settings() = 0;
};

}  // namespace sandtin
