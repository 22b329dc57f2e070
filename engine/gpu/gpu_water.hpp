#pragma once
// Water by virtual pipes on the GPU over a TinMirror (issue 40, item 6): the scheme of
// water/virtual_pipes.hpp, its CPU reference in double, run vertex-parallel in float on the
// mirror's CSR rows (shaders/water_*.comp). Per step, two dispatches over the vertices:
//  - water_flux: each vertex updates the pipes of its row from the surface difference and its
//    previous signed flux, keeps its outflows and scales them to what it holds;
//  - water_depth: each vertex gathers its neighbours' outflows towards it through the reverse
//    slots and updates its depth, compensated (the float residual keeps what the depth could
//    not take), so the volume sum(area depth + residual) is exact to rounding.
// After a run, one more dispatch measures the stability limit (the CFL step), the wet and the
// flowing vertices; a run after one that left the terrain dry and still records nothing and
// never touches the GPU, until the mirror uploads water from the CPU again.
//
// The depths are the mirror's water-depth buffer, fed by the journal like every attribute:
// water the CPU puts on the terrain (sources, undo, loading) reaches the GPU at sync(), and
// copy_depths_into() hands the GPU's water back to the terrain (do so before the terrain is
// edited elsewhere: the next sync puts the terrain's depths back on every vertex it uploads).
// The water also reads the journal itself, through a reader of its own: a re-triangulation
// starts the pipes' fluxes from rest (as the CPU's LiveWater rebuilds its pipes), a vertex
// the CPU changed drops its float residual (its depth is the terrain's again), and water
// the CPU put down wakes a dry GPU water.
// Units: metres, seconds, m³.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/tin_mirror.hpp"
#include "tin/change_reader.hpp"

namespace sandtin::gpu {

struct GpuWaterSettings {
    double gravity = 9.81;  ///< m/s², > 0
    double friction = 0.5;  ///< 1/s, >= 0, as VirtualPipeOptions::friction
    double courant = 0.5;   ///< stable_time_step()'s fraction of the limit, in (0, 1]
};

struct GpuWaterRun {
    int steps = 0;                  ///< steps recorded (0: the water was dry and still)
    uint64_t dispatches = 0;        ///< dispatch commands recorded
    uint32_t wet = 0;               ///< vertices holding water after the run
    uint32_t flowing = 0;           ///< vertices still sending water after the run
    uint64_t outflows_limited = 0;  ///< vertex-steps whose outflows were scaled down
};

/// Work recorded after each water step, in the same submission (the sediment the water
/// carries: gpu_sediment.hpp).
class WaterStepHook {
  public:
    virtual ~WaterStepHook() = default;
    /// Before the run's submission is recorded (sync buffers, bind).
    virtual void prepare() = 0;
    /// After the step that wrote the `parity` half of the fluxes, with the new depths.
    virtual void record_step(VkCommandBuffer cb, uint32_t parity, double dt) = 0;
};

class GpuWater {
  public:
    /// Syncs the mirror (the water on the terrain now is the GPU's). Throws GpuError for
    /// settings out of range.
    GpuWater(TinMirror& mirror, GpuWaterSettings settings = {});
    ~GpuWater();
    GpuWater(const GpuWater&) = delete;
    GpuWater& operator=(const GpuWater&) = delete;

    /// Open border per vertex id (m of border each vertex lets water out over; 0 closed), as
    /// water/water_borders.hpp's outflow_widths computes for the open sides. Throws GpuError
    /// for a negative or non-finite width.
    void set_outflow_widths(std::span<const double> metres_per_vertex);

    /// Syncs the mirror, then advances the water `steps` steps of `dt` seconds (finite, > 0;
    /// GpuError otherwise) in one submission, and waits. Stable for dt up to
    /// stable_time_step() / courant. Dry, still water records nothing.
    GpuWaterRun run(int steps, double dt, WaterStepHook* hook = nullptr);
    /// The longest stable step (s) for the water now, times the courant setting; infinite
    /// when there is no water. Measures on the GPU when the water changed since the last run.
    double stable_time_step();
    /// Whether a run would do work: the last run or measurement left water or a flow, or the
    /// mirror has uploaded water since. A terrain that never held water is never active.
    bool active() const { return active_; }
    /// Deepest water after the last run or measurement (m).
    double deepest() const { return deepest_; }

    /// The depth buffer (m) per vertex id as of the last run or sync, mirror vertex capacity
    /// long.
    std::vector<float> read_depths() const;
    /// m³ the GPU holds: sum(area x depth + residual) in double over the live vertices.
    double volume() const;
    /// m³ that left through the open border since construction.
    double volume_left() const;
    /// Writes the GPU's depths into the mirrored terrain (Tin::set_water_depth, journaled) for
    /// the live vertices whose depth differs; returns how many were written.
    std::size_t copy_depths_into(Tin& tin) const;

    uint64_t dispatches_recorded() const { return dispatches_total_; }
    /// The outflows, two halves of edge_capacity() floats (m³/s): q[half x capacity + k] is
    /// what the row's vertex sends along directed edge k.
    VkBuffer flux_buffer() const { return q_.get(); }
    uint32_t edge_capacity() const { return edge_capacity_; }
    TinMirror& mirror() const { return mirror_; }

  private:
    struct Push {
        uint32_t vertex_count;
        uint32_t edge_capacity;
        uint32_t parity;
        uint32_t pad;
        float dt;
        float gravity;
        float damping;
        float pad2;
    };
    /// Syncs the mirror and brings the water's own buffers and bindings up to date with it.
    void follow_mirror();
    void ensure_buffers();
    void record_measure(VkCommandBuffer cb, const Push& push);
    static constexpr uint32_t kControlWords = 8;  ///< shaders/water_common.glsl's C_* words
    /// Reads the control words the last submission copied back and takes the limit, the
    /// deepest water and whether anything is wet or flowing from them.
    std::array<uint32_t, kControlWords> take_measure();
    Push push(double dt) const;

    VulkanContext& context_;
    TinMirror& mirror_;
    GpuWaterSettings settings_;
    ChangeReader changes_;  ///< the terrain's journal, read for the water alone
    ComputeKernel flux_;
    ComputeKernel depth_;
    ComputeKernel measure_;
    Buffer control_;       ///< device: the control words (shaders/water_common.glsl)
    Buffer control_host_;  ///< their read-back
    Buffer q_;             ///< 2 x edge capacity outflows (m³/s)
    Buffer keep_, residual_, left_, border_;  ///< per vertex id
    std::vector<float> border_widths_;        ///< host copy of border_, vertex capacity long
    bool border_dirty_ = false;
    uint32_t vertex_capacity_ = 0, edge_capacity_ = 0;
    uint64_t bound_generation_ = UINT64_MAX;
    uint32_t parity_ = 0;
    bool active_ = false;    ///< as of the last measurement
    bool measured_ = false;  ///< limit_ is current
    double limit_ = 0.0;
    double deepest_ = 0.0;
    uint64_t dispatches_total_ = 0;
};

}  // namespace sandtin::gpu
