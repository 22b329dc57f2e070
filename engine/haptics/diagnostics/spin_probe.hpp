#pragma once
// A machine-jitter probe in the style of hwlatdetect: a thread (SCHED_FIFO when granted, pinned
// when asked) reads the monotonic clock in a tight loop with no other work, and every gap
// between two consecutive reads longer than a threshold is time the CPU was taken from it:
// by interrupts, by higher-priority kernel threads, or (on a virtual machine) by the hypervisor
// not running the virtual CPU. It spins in bursts with sleeps between them, so that it never
// monopolises a CPU (nor trips the kernel's real-time throttling at 95 %).
//
// GapStats is the pure part (fed timestamps, no clock), so its statistics can be tested on
// synthetic series; run_spin_probe drives it with the real clock.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "haptics/diagnostics/os_counters.hpp"
#include "haptics/realtime_thread.hpp"

namespace sandtin::haptics {

/// Gaps between consecutive clock reads.
class GapStats {
  public:
    /// Gaps longer than `threshold_ns` (> 0) count as stolen time.
    explicit GapStats(std::int64_t threshold_ns);

    /// Starts a burst at `t_ns`: the gap to the previous read is not counted (a sleep).
    void begin(std::int64_t t_ns);
    /// The next clock read of the current burst.
    void read(std::int64_t t_ns);

    /// Edges of the buckets of `bucket_counts` (ns): [threshold, 100us), [100us, 500us),
    /// [500us, 1ms), [1ms, 2ms), [2ms, 10ms), [10ms, inf).
    static constexpr std::array<std::int64_t, 5> kBucketEdgesNs{100'000, 500'000, 1'000'000,
                                                                2'000'000, 10'000'000};
    std::int64_t observed_ns() const { return observed_ns_; }  ///< time spent in bursts
    std::int64_t stolen_ns() const { return stolen_ns_; }      ///< sum of counted gaps
    std::int64_t max_gap_ns() const { return max_gap_ns_; }
    std::uint64_t gaps() const { return gaps_; }
    const std::array<std::uint64_t, 6>& bucket_counts() const { return buckets_; }

  private:
    std::int64_t threshold_ns_;
    std::int64_t last_ = 0;
    bool in_burst_ = false;
    std::int64_t observed_ns_ = 0;
    std::int64_t stolen_ns_ = 0;
    std::int64_t max_gap_ns_ = 0;
    std::uint64_t gaps_ = 0;
    std::array<std::uint64_t, 6> buckets_{};
};

struct SpinProbeOptions {
    double seconds = 10.0;
    std::int64_t burst_ns = 10'000'000;  ///< spin this long...
    std::int64_t sleep_ns = 10'000'000;  ///< ...then sleep this long
    std::int64_t threshold_ns = 20'000;
    RealtimeRequest realtime;  ///< cpu: the CPU to probe (-1: wherever it runs)
};

struct SpinProbeResult {
    GapStats gaps{1};
    RealtimeGrant grant;
    ThreadCounters during;  ///< the probe thread's scheduler counters over the run
    /// Steal time of each CPU over the run (ns; empty when unavailable).
    std::vector<std::int64_t> steal_ns;
};

/// Runs the probe on a new thread and waits for it. Throws std::invalid_argument for bad
/// options.
SpinProbeResult run_spin_probe(const SpinProbeOptions& options);

}  // namespace sandtin::haptics
