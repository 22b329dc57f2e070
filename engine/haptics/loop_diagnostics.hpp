#pragma once
// The force loop's OS jitter diagnostics, attached to it as its LoopObserver: the phases of
// every tick (loop_jitter.hpp), to attribute late ticks, and the loop thread's scheduler
// counters and page faults from just before the first tick to just after the last
// (os_counters.hpp). `sandtin bench haptics` and `sandtin haptics serve` attach them; the loop
// itself runs without them.

#include <cstddef>
#include <vector>

#include "haptics/force_loop.hpp"
#include "haptics/loop_jitter.hpp"
#include "haptics/loop_observer.hpp"
#include "haptics/os_counters.hpp"

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
