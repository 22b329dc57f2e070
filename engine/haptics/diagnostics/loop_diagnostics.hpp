#pragma once
// engine/haptics/diagnostics: the OS jitter diagnostics of the force loop. They measure what
// the operating system and the machine did to the loop thread, so a late tick can be
// attributed instead of guessed at, and take no part in a tick's force:
//  - LoopDiagnostics (here), attached to a ForceLoop as its LoopObserver: the phases of every
//    tick (loop_jitter.hpp) and the loop thread's scheduler counters and page faults from just
//    before the first tick to just after the last (os_counters.hpp);
//  - SchedSampler (sched_sampler.hpp): a low-rate thread that watches the kernel's run queue
//    and the hypervisor's steal time, to match late ticks against;
//  - run_spin_probe (spin_probe.hpp): the machine's own jitter, with no loop at all;
//  - CpuWakeLatencyHold (cpu_wake_latency.hpp): keeps idle CPUs from sleeping deeply while a
//    run is measured.
// Dependencies point from this room to the loop, never back: to its observer interface and
// clock (haptics/loop_observer.hpp), its config (haptics/force_loop.hpp, for the period that
// makes a tick late) and its thread set-up (haptics/realtime_thread.hpp, for the probe). The
// loop runs, and is tested, without this room; `sandtin bench haptics` and `sandtin haptics
// serve` attach it.

#include <cstddef>
#include <vector>

#include "haptics/diagnostics/loop_jitter.hpp"
#include "haptics/diagnostics/os_counters.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/loop_observer.hpp"

namespace sandtin::haptics {

class LoopDiagnostics final : public LoopObserver {
  public:
    /// For a loop with `config` (throws std::invalid_argument for a config ForceLoop refuses);
    /// keeps the first `late_tick_capacity` late ticks (period > 1.5 periods) whole. Give it to
    /// the loop's constructor; it must outlive the loop.
    explicit LoopDiagnostics(const ForceLoopConfig& config, std::size_t late_tick_capacity = 64);

    // ---- After the loop has stopped ----
    /// Where the ticks' time went.
    JitterSummary jitter() const { return jitter_.summary(); }
    /// The first late_tick_capacity ticks whose period exceeded 1.5 periods.
    const std::vector<TickPhases>& late_ticks() const { return jitter_.late_ticks(); }
    /// The loop thread's scheduler counters and faults from just before the first tick to just
    /// after the last (the stop ramp included).
    const ThreadCounters& during_ticks() const { return during_ticks_; }

    // ---- LoopObserver, called by the loop's threads ----
    void thread_started() override;
    void ticks_starting() override;
    void ticked(const TickPhases& phases) override;  ///< never allocates
    void ticks_ended() override;

  private:
    JitterStats jitter_;
    ThreadCounters before_;
    ThreadCounters during_ticks_;
};

}  // namespace sandtin::haptics
