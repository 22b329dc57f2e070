#pragma once
// Talus relaxation on the GPU over a TinMirror: the two-phase Jacobi schedule of
// physics/talus_solver.hpp (outflow per directed edge, then gather), in float, over a compacted
// active list kept on the GPU and dispatched indirectly. Per iteration: outflow (active list;
// talus_outflow.comp under the edge rule, talus_face_outflow.comp under the face rule, picked
// by settings().parameters.rule at each run),
// gather (receivers), age (active list), activate (changed vertices and neighbours) and three
// one-invocation control steps that write the next indirect arguments. A terrain at rest
// records nothing at all: run() returns without touching the GPU when the last known active
// count is zero and no activation is pending.
//
// Heights on the GPU are the mirror's height buffer: after run(), read_back() returns the
// vertices that changed (height and texture-slide offset) so the CPU TIN can be updated.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/compute_kernel.hpp"
#include "gpu/kernel_timer.hpp"
#include "gpu/tin_mirror.hpp"
#include "physics/talus_kernel.hpp"

namespace sandtin::gpu {

struct GpuRelaxationSettings {
    TalusParameters parameters;
    int quiet_iterations = 3;  // K, as TalusSettings::quiet_iterations
    // gamma of texture sliding: texture units per metre of transported height; 0 = off.
    double slide_gain = 0.0;
    // TalusSettings::randomness and seed: the same per-vertex, per-iteration jitter as the CPU
    // (splitmix64 of seed, vertex and the count of iterations that had work).
    double randomness = 0.0;
    uint64_t seed = 1;
    bool profile = false;  // per-kernel timestamps (KernelTimer), for benchmarks
};

struct GpuRunStats {
    int iterations = 0;           // iterations recorded
    uint64_t dispatches = 0;      // dispatch commands recorded
    uint32_t active_after = 0;    // active vertices after the run
    uint64_t vertex_updates = 0;  // active vertices processed, summed over the iterations
    uint64_t changed = 0;         // height changes, summed over the iterations
};

// One entry of read_back() (shaders/talus_common.glsl PackedVertex).
struct TouchedVertex {
    static constexpr uint32_t kSurfaceChanged = 2;  // touched bit: height or slide changed

    uint32_t id = 0;
    float height = 0.0f;
    float slide_x = 0.0f;
    float slide_y = 0.0f;
    float moved = 0.0f;  // m³ the vertex sent since the previous read_back
    uint32_t touched = 0;

    // False when the vertex is listed only for what it sent (its height and slide are as the
    // previous read_back left them).
    bool surface_changed() const { return (touched & kSurfaceChanged) != 0; }
};

class GpuRelaxation {
  public:
    GpuRelaxation(TinMirror& mirror, GpuRelaxationSettings settings);
    ~GpuRelaxation();
    GpuRelaxation(const GpuRelaxation&) = delete;
    GpuRelaxation& operator=(const GpuRelaxation&) = delete;

    GpuRelaxationSettings& settings() { return settings_; }
    // Queues vertices to activate before the next iteration (ActiveSet::activate).
    void activate(std::span<const uint32_t> vertices);
    // Runs up to `iterations` iterations in one submission and waits for it.
    GpuRunStats run(int iterations);
    // Active vertices after the last run (0: at rest), plus pending activations.
    uint32_t active_count() const { return known_active_ + static_cast<uint32_t>(pending_.size()); }
    bool at_rest() const { return active_count() == 0; }

    // Vertices whose height or slide changed since the previous read_back (their GPU values),
    // and those that sent sand (with the volume): every vertex with something to report.
    std::vector<TouchedVertex> read_back();
    // Vertices the relocation radius asked to refine around since the previous call.
    std::vector<uint32_t> take_split_requests();
    // The whole height buffer (tests, exports); size = mirror vertex capacity.
    std::vector<float> read_heights() const;
    std::vector<float> read_slides() const;  // x, y per vertex

    uint64_t dispatches_recorded() const { return dispatches_total_; }
    const KernelTimer& timer() const { return *timer_; }
    KernelTimer& timer() { return *timer_; }

  private:
    struct Push {
        uint32_t iter;
        uint32_t capacity;
        uint32_t mode;
        uint32_t quiet_limit;
        float damping;
        float rest_tolerance;
        float r_limit;
        float slide_gain;
        uint32_t seed_lo;
        uint32_t seed_hi;
        float randomness;
        float settle_margin;
        uint32_t split_batch;
    };
    void ensure_buffers();
    void bind_all();
    Push push(uint32_t mode) const;
    void read_control(std::vector<uint32_t>& out) const;

    VulkanContext& context_;
    TinMirror& mirror_;
    GpuRelaxationSettings settings_;
    ComputeKernel outflow_;
    ComputeKernel face_outflow_;  // phase 1 under SlopeRule::Face (talus_face_outflow.comp)
    ComputeKernel gather_;
    ComputeKernel age_;
    ComputeKernel activate_;
    ComputeKernel control_;
    ComputeKernel pack_;
    std::unique_ptr<KernelTimer> timer_;
    Buffer control_buf_;   // device: control words + indirect arguments
    Buffer control_host_;  // read-back copy of the control words
    Buffer q_;
    Buffer out_;
    Buffer state_;
    Buffer lists_;
    Buffer packed_;
    Buffer seed_upload_;          // host list of pending activations
    Buffer readback_;             // host copy of packed entries
    uint32_t capacity_ = 0;       // vertex capacity the state buffers are laid out for
    uint32_t edge_capacity_ = 0;  // edge capacity of q_
    uint64_t bound_generation_ = UINT64_MAX;
    uint32_t iteration_ = 0;  // stamps; 0 is never used
    // Stamp of the split requests since the last take_split_requests(): a vertex is listed
    // once per batch, so the list (one slot per vertex) cannot overflow. 0 is never used.
    uint32_t split_batch_ = 1;
    uint32_t known_active_ = 0;
    std::vector<uint32_t> pending_;
    uint64_t dispatches_total_ = 0;
};

}  // namespace sandtin::gpu
