#pragma once
// Moisture in the sand on the GPU over a TinMirror (issue 40, item 6): the scheme of
// water/moisture_diffusion.hpp (its CPU reference, in double), run vertex-parallel in float
// on the mirror's moisture buffer and CSR rows (shaders/moisture_*.comp):
//  - moisture_wet (optional): water at least a given depth deep wets the sand under it;
//  - moisture_spread, once per sub-step: moisture spreads along the cotangent-weighted edges
//    into drier sand and dries by the exact decay over the sub-step;
//  - moisture_finish: with drying, moisture below kNegligibleMoisture is dry (0); counts what
//    is still wet.
// The sub-step follows the CPU's rule (the bound of the vertex at 1 % from the stiffest, at
// least 1/64 of the median's, the seconds split into equal sub-steps), taken over every
// vertex with edges rather than only those the moisture reaches: the same on a uniform mesh,
// shorter (never longer) where the wet region has no slivers but the terrain elsewhere does.
//
// Fed by the journal as every attribute: moisture the CPU sets reaches the GPU at sync();
// copy_moisture_into() hands the GPU's moisture back (journaled). A terrain with no moisture
// costs nothing: a run that leaves every vertex dry, or a terrain that never had moisture,
// records no dispatch until the CPU puts moisture (or, for wetting, water) on it again.
// Units: metres, seconds; moisture is a saturation in [0, 1].

#include <array>
#include <cstdint>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/tin_mirror.hpp"
#include "tin/change_reader.hpp"
#include "water/moisture_diffusion.hpp"

namespace sandtin::gpu {

/// Water wetting the sand under it at the start of a run (LiveWaterSettings' wet_depth and
/// wet_moisture): depth > 0 m, moisture in [0, 1].
struct WettingByWater {
    double depth = 1e-3;
    float moisture = 1.0f;
};

struct GpuMoistureRun {
    std::size_t sub_steps = 0;     ///< 0: nothing was wet (nothing recorded)
    uint64_t dispatches = 0;       ///< dispatch commands recorded
    uint32_t wet = 0;              ///< vertices with moisture > 0 after the run
    float wettest = 0.0f;          ///< the largest moisture after the run
    uint64_t vertices_slowed = 0;  ///< vertex-sub-steps whose exchanges were slowed
};

class GpuMoisture {
  public:
    /// Syncs the mirror. Throws GpuError for settings out of range (as
    /// spread_and_dry_moisture: diffusivity finite >= 0, half-life > 0).
    GpuMoisture(TinMirror& mirror, MoistureSettings settings = {});
    ~GpuMoisture();
    GpuMoisture(const GpuMoisture&) = delete;
    GpuMoisture& operator=(const GpuMoisture&) = delete;

    /// Syncs the mirror, optionally wets the sand under the water, then lets `seconds` pass
    /// (finite, >= 0; GpuError otherwise) in one submission, and waits.
    GpuMoistureRun run(double seconds, const WettingByWater* wetting = nullptr);
    /// The sub-step (s) a run takes at most, from the mirror's current triangulation; +inf
    /// without spreading (diffusivity 0 or no edge).
    double sub_step();
    /// Whether a run would do work (see above).
    bool active() const { return active_; }

    /// The moisture buffer per vertex id, mirror vertex capacity long.
    std::vector<float> read_moisture() const;
    /// sum(area x moisture) over the live vertices (m²), in double from the GPU's floats.
    double total() const;
    /// Writes the GPU's moisture into the mirrored terrain (Tin::set_moisture, journaled) for
    /// the live vertices whose moisture differs; returns how many were written.
    std::size_t copy_moisture_into(Tin& tin) const;

    uint64_t dispatches_recorded() const { return dispatches_total_; }

  private:
    struct Push {
        uint32_t vertex_count;
        uint32_t parity;
        uint32_t drying;
        uint32_t pad;
        float d_dt;
        float decay;
        float threshold;
        float wet_depth;
        float wet_moisture;
    };
    void follow_mirror();
    void ensure_buffers();
    /// Computes the weight sums and ratios (after a re-triangulation) and the sub-step's bound.
    void measure_weights();
    Push push() const;
    /// Whether the terrain holds water anywhere (on the CPU's side, which the mirror follows).
    bool any_water() const;

    static constexpr uint32_t kControlWords = 4;  ///< shaders/moisture_common.glsl's C_* words

    VulkanContext& context_;
    TinMirror& mirror_;
    MoistureSettings settings_;
    ChangeReader changes_;  ///< the terrain's journal, read for the moisture alone
    ComputeKernel weights_;
    ComputeKernel wet_;
    ComputeKernel spread_;
    ComputeKernel finish_;
    Buffer control_;
    Buffer control_host_;
    Buffer scratch_, weight_sum_, ratio_;  ///< per vertex id
    uint32_t vertex_capacity_ = 0;
    uint64_t bound_generation_ = UINT64_MAX;
    bool weights_stale_ = true;
    double bound_ratio_ = 0.0;  ///< A / sum w of the vertex the sub-step follows (m²/(m²/m²))
    bool active_ = false;
    uint64_t dispatches_total_ = 0;
};

}  // namespace sandtin::gpu
