#pragma once
// What the operating system says happened to a thread and to the CPUs, read before and after
// a run so a late tick can be told apart from a loop that did too much:
//  - the thread's scheduler statistics (/proc/thread-self/schedstat): time on a CPU, time
//    runnable but waiting for a CPU in this kernel's run queue, number of times scheduled;
//  - its context switches and page faults (getrusage(RUSAGE_THREAD));
//  - each CPU's steal time (/proc/stat): time the hypervisor ran something else while this
//    virtual CPU wanted to run. The kernel reports it in USER_HZ ticks (10 ms here).
// Linux only. A field the system does not provide stays at -1; reading never throws.
// The parsers take the files' text so they can be tested without the files.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sandtin::haptics {

struct SchedStat {
    std::int64_t cpu_ns = -1;        ///< time spent running
    std::int64_t run_delay_ns = -1;  ///< time spent runnable, waiting in a run queue
    std::int64_t slices = -1;        ///< times it was scheduled in
};

/// Parses /proc/<pid>/task/<tid>/schedstat: three unsigned decimal fields.
std::optional<SchedStat> parse_schedstat(std::string_view text);

/// Parses /proc/stat's per-CPU lines ("cpuN user nice system idle iowait irq softirq steal
/// ..."): the steal time of CPU N at index N, in nanoseconds (ticks * 1e9 / ticks_per_second).
/// The aggregate "cpu" line is skipped. Returns nullopt when no per-CPU line has a steal field.
std::optional<std::vector<std::int64_t>> parse_cpu_steal_ns(std::string_view proc_stat,
                                                            long ticks_per_second);

struct ThreadCounters {
    SchedStat sched;
    std::int64_t voluntary_switches = -1;    ///< the thread blocked or slept
    std::int64_t involuntary_switches = -1;  ///< the thread was preempted
    std::int64_t minor_faults = -1;
    std::int64_t major_faults = -1;
};

/// The calling thread's counters.
ThreadCounters read_this_thread_counters();

/// `after - before` field by field (-1 where either side is unknown).
ThreadCounters difference(const ThreadCounters& after, const ThreadCounters& before);

/// Steal time per CPU now (empty when unavailable).
std::vector<std::int64_t> read_cpu_steal_ns();

/// The whole text of a (proc) file, or nullopt.
std::optional<std::string> read_small_file(const char* path);

}  // namespace sandtin::haptics
