#pragma once
// What the force loop shows of itself to an observer on its threads: its clock, the timing of
// every tick, and when its ticking starts and ends. The loop measures the timing in any case
// (it is how it waits for a deadline); what is made of it is the observer's. The OS jitter
// diagnostics (diagnostics/loop_diagnostics.hpp) are such an observer: they attribute late
// ticks to their phases and read the loop thread's scheduler counters around the ticks, so
// they depend on this header and the loop does not depend on them.

#include <cstdint>

namespace sandtin::haptics {

/// Monotonic clock in nanoseconds (steady_clock): the loop's time base.
std::int64_t monotonic_ns();

/// One tick's timing. Times are monotonic nanoseconds.
struct TickPhases {
    std::uint64_t tick = 0;
    std::int64_t start_ns = 0;      ///< when the tick started (the spin ended)
    std::int64_t period_ns = 0;     ///< start - previous start
    std::int64_t lateness_ns = 0;   ///< start - deadline, >= 0
    std::int64_t work_ns = 0;       ///< the previous tick's body
    bool slept = false;             ///< false when the previous body ended past the sleep point
    std::int64_t wake_late_ns = 0;  ///< sleep returned this long after its planned end; 0 if !slept
    std::int64_t spin_gap_ns = 0;   ///< largest gap between consecutive clock reads in the spin
    int cpu = -1;                   ///< CPU the tick started on (-1 unknown)
};

/// Attached to a ForceLoop at construction; sees every run of it. The calls of one run never
/// overlap and are ordered as listed.
class LoopObserver {
  public:
    virtual ~LoopObserver() = default;

    /// On the loop thread once it has set itself up, before the backup thread (if any) starts
    /// and before any tick.
    virtual void thread_started() {}
    /// On the loop thread just before it waits for its first tick (the backup thread runs).
    virtual void ticks_starting() {}
    /// Every tick after the first, at its start, by whichever thread runs it. On the tick
    /// path: it must not block, allocate or make system calls.
    virtual void ticked(const TickPhases& /*phases*/) {}
    /// On the loop thread after the last tick, once the backup thread has ended.
    virtual void ticks_ended() {}
};

}  // namespace sandtin::haptics
