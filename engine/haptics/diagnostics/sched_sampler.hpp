#pragma once
// A low-rate observer thread for benchmarks: every `interval` it reads the force-loop thread's
// scheduler statistics (time waiting in this kernel's run queue) and every CPU's steal time
// (time the hypervisor did not run the virtual CPU), with a monotonic time stamp. A late tick
// can then be matched to what happened during it: if the loop thread waited in the run queue,
// this kernel ran something else on its CPU; if steal time grew, the host took the CPU; if
// neither, the time went elsewhere (interrupts, or the loop itself).
//
// The sampler runs at normal priority on whatever CPU is free, never touches the loop's data
// and stores into preallocated memory. Steal time moves in USER_HZ steps (10 ms), so it
// attributes long stalls only; run-queue delay is in nanoseconds.

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace sandtin::haptics {

inline constexpr std::size_t kSampledCpus = 8;

struct SchedSample {
    std::int64_t read_start_ns = 0;  ///< monotonic, before the counters were read
    std::int64_t time_ns = 0;        ///< monotonic, after they were read
    std::int64_t run_delay_ns = -1;  ///< the observed thread's cumulative run-queue wait
    std::array<std::int64_t, kSampledCpus> steal_ns{};  ///< cumulative, per CPU (-1 = none)
};

/// What happened in [from_ns, to_ns], measured between the last sample read wholly at or
/// before `from_ns` and the first read wholly at or after `to_ns` (so over `span_ns` >= the
/// window: the counts are upper bounds of what happened in the window itself).
struct WindowAttribution {
    bool covered = false;  ///< samples bracket the window
    std::int64_t span_ns = 0;
    std::int64_t run_delay_ns = 0;       ///< the loop thread waited in the run queue
    std::int64_t steal_on_cpu_ns = 0;    ///< steal of `cpu` (0 when the cpu is unknown)
    std::int64_t steal_all_cpus_ns = 0;  ///< summed over CPUs
};

/// `samples` in increasing time order. `cpu` < 0 means unknown.
WindowAttribution attribute_window(const std::vector<SchedSample>& samples, std::int64_t from_ns,
                                   std::int64_t to_ns, int cpu);

class SchedSampler {
  public:
    /// Observes thread `tid` of this process; keeps up to `capacity` samples.
    SchedSampler(int tid, std::int64_t interval_ns, std::size_t capacity);
    ~SchedSampler();
    SchedSampler(const SchedSampler&) = delete;
    SchedSampler& operator=(const SchedSampler&) = delete;

    void start();
    void stop();  ///< idempotent
    /// After stop().
    const std::vector<SchedSample>& samples() const { return samples_; }
    bool available() const { return available_; }  ///< the proc files could be read

  private:
    void run();

    int tid_;
    std::int64_t interval_ns_;
    std::vector<SchedSample> samples_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
    bool available_ = false;
};

}  // namespace sandtin::haptics
