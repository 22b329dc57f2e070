#pragma once
// One force-loop tick, without threads or clocks of its own, so the same code runs in the
// 1 kHz thread, in lock-step tests and in offline replays.
//
// On top of the memoryless model (force_model.hpp) it adds:
//  - Interpolation between geometry updates (seed 000 Eq. 7.15, seed 004 §5.3.7):
//      F_out = F_old + (F - F_old) it / it_p,
//    it_p = ticks between the last two snapshot arrivals, it = ticks since the last one. The
//    pen keeps moving while we blend, so we blend offsets rather than frozen values: at an
//    arrival, Δ = (what the old snapshot gives now, still blending) - (what the new one gives
//    now), and the output is model(new snapshot, pen) + Δ max(0, 1 - it / it_p). The output is
//    continuous at every arrival and equals the new model once it reaches it_p.
//  - Zero force out of contact (the seeds' rule beats the blend).
//  - Clamp to the device's maximum force.
//  - Staleness: when the latest snapshot is older than `stale_after_ns` (the simulation
//    stalled) the output gain ramps linearly to 0 over `ramp_ns`, and back up the same way
//    when snapshots resume, so the force never jumps (seed 004 §5.3: a 0-to-10 N jump within
//    1 ms can make the user drop the stylus).

#include <cstdint>

#include "geom/vec3.hpp"
#include "haptics/force_model.hpp"
#include "haptics/haptic_snapshot.hpp"

namespace sandtin::haptics {

struct ForceRendererConfig {
    ForceModelParams model;
    double rate_hz = 1000.0;  ///< tick rate; the gel drag's velocity uses the nominal period
    std::int64_t stale_after_ns = 100'000'000;  ///< 100 ms: six missed 60 Hz frames
    std::int64_t ramp_ns = 200'000'000;         ///< 200 ms from full force to zero
    /// Bounds on it_p (ticks). The seed blends over the interval between the last two
    /// updates, about 17 ticks at its 60 Hz geometry rate; the lower bound keeps at least that
    /// much smoothing when our simulation publishes faster (a stamp that digs away the sand
    /// under the tool drops the force by several newtons in one snapshot). The upper bound
    /// keeps a long stall from making the next update blend in for seconds.
    std::uint32_t min_blend_ticks = 16;
    std::uint32_t max_blend_ticks = 250;
    /// it_p for the first snapshot (no previous interval): one 60 Hz frame at 1 kHz.
    std::uint32_t first_blend_ticks = 16;
};

struct TickOutput {
    Vec3 force;            ///< N, what goes to the device
    bool contact = false;  ///< the current snapshot's model is in contact
    bool stale = false;    ///< the latest snapshot is older than stale_after_ns (or none yet)
    double gain = 0.0;     ///< the staleness ramp, in [0, 1]
    std::uint64_t snapshot_sequence = 0;
};

class ForceRenderer {
  public:
    /// Throws std::invalid_argument for a non-positive rate, ramp or negative bounds.
    explicit ForceRenderer(const ForceRendererConfig& config);

    /// One tick: the device point (m), the monotonic time (ns) and, when the simulation
    /// published a new snapshot since the last tick, that snapshot (else nullptr).
    TickOutput tick(const Vec3& position, std::int64_t now_ns, const HapticSnapshot* fresh);

    const ForceRendererConfig& config() const { return config_; }
    std::uint64_t ticks() const { return tick_; }

  private:
    ForceRendererConfig config_;
    PreparedSnapshot current_{};
    bool has_snapshot_ = false;
    std::uint64_t tick_ = 0;
    std::uint64_t last_arrival_tick_ = 0;
    std::uint32_t blend_ticks_ = 1;  // it_p
    Vec3 blend_offset_;              // Δ
    Vec3 previous_position_;
    bool has_previous_ = false;
    double gain_ = 0.0;
    double gain_step_ = 0.0;  // per tick
};

}  // namespace sandtin::haptics
