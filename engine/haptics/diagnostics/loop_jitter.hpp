#pragma once
// Where a force-loop tick's time went, so that a late tick can be attributed instead of
// guessed at. Each tick the loop measures, with the monotonic clock only (no other system
// call in the tick path):
//  - work: how long the previous tick's body ran (device read, render, write, publish);
//  - wake lateness: how long after its planned end the sleep returned. Large values mean the
//    thread was runnable but not running (the kernel ran something else on its CPU, or the
//    hypervisor did not run the virtual CPU): the cyclictest measurement;
//  - spin gap: the largest gap between two consecutive clock reads while spinning to the
//    deadline. A spinning SCHED_FIFO thread is only interrupted by interrupts, higher-priority
//    kernel threads or the hypervisor, so a gap of more than a few microseconds is time the
//    machine, not the loop, took: the hwlatdetect measurement, over the spin's share of time.
// The loop hands them over as TickPhases (loop_observer.hpp); JitterStats keeps their maxima
// and the first few late ticks with their phases. It never allocates after construction, so it can
// run in the tick path.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "haptics/loop_observer.hpp"

namespace sandtin::haptics {

/// Which phase of a late tick took the time: the largest of work, wake lateness, spin gap.
enum class LateCause : std::uint8_t { Work, Wakeup, SpinGap };
const char* to_string(LateCause cause);
LateCause late_cause(const TickPhases& t);

struct JitterSummary {
    std::uint64_t ticks = 0;
    std::int64_t max_work_ns = 0;
    std::int64_t max_wake_late_ns = 0;
    std::int64_t max_spin_gap_ns = 0;
    /// Sleeps that returned after the tick's deadline: the spin could not absorb them.
    std::uint64_t wakes_after_deadline = 0;
    /// Spin gaps longer than JitterStats::kLongGapNs, and their total.
    std::uint64_t long_spin_gaps = 0;
    std::int64_t long_spin_gap_total_ns = 0;
    /// Ticks whose period exceeded the late threshold, by cause.
    std::uint64_t late_ticks = 0;
    std::uint64_t late_by_work = 0;
    std::uint64_t late_by_wakeup = 0;
    std::uint64_t late_by_spin_gap = 0;
    std::uint64_t late_ticks_not_kept = 0;  ///< beyond the event capacity
    TickPhases worst;                       ///< the tick with the longest period
};

class JitterStats {
  public:
    static constexpr std::int64_t kLongGapNs = 50'000;

    /// A tick is late when its period exceeds `late_threshold_ns` (> 0); the first
    /// `event_capacity` late ticks are kept whole.
    JitterStats(std::int64_t late_threshold_ns, std::size_t event_capacity);

    void add(const TickPhases& t);  ///< never allocates
    JitterSummary summary() const { return summary_; }
    const std::vector<TickPhases>& late_ticks() const { return events_; }
    std::int64_t late_threshold_ns() const { return threshold_ns_; }
    void clear();

  private:
    std::int64_t threshold_ns_;
    JitterSummary summary_;
    std::vector<TickPhases> events_;  // capacity fixed at construction
};

}  // namespace sandtin::haptics
