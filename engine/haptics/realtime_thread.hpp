#pragma once
// Making the calling thread fit for a hard 1 kHz loop, each step optional and each refusal
// reported rather than fatal (an unprivileged editor still gets a working loop):
//  - SCHED_FIFO, so ordinary threads cannot delay it;
//  - pinning to one CPU, so it never migrates and the simulation can be kept off that CPU;
//  - timer slack of 1 ns (PR_SET_TIMERSLACK), so a non-real-time sleep is not rounded up by
//    the default 50 us (real-time threads have no slack anyway);
//  - mlockall(MCL_CURRENT | MCL_FUTURE): no page of the process is ever paged out and new
//    mappings are populated when made, so the loop cannot take a page fault that waits for
//    another thread's mmap/munmap (they hold the address-space lock). Process-wide: opt in;
//  - pre-faulting the top of its own stack, so the first deep call does not fault.
// The system calls go through RealtimeCalls so tests can refuse them.

#include <cstddef>
#include <string>

namespace sandtin::haptics {

struct RealtimeRequest {
    bool fifo = true;
    /// SCHED_FIFO priority as an offset above the minimum (1 + 10 = 11 of 99 on Linux): above
    /// ordinary threads, below the kernel's own real-time threads.
    int fifo_priority_offset = 10;
    int cpu = -1;  ///< pin to this CPU; -1 = do not pin
    bool timer_slack = true;
    bool lock_memory = false;  ///< process-wide mlockall, see above
    std::size_t prefault_stack_bytes = 256 * 1024;
};

struct RealtimeGrant {
    bool fifo = false;
    int cpu = -1;  ///< the CPU pinned to, -1 = not pinned
    bool timer_slack = false;
    bool memory_locked = false;
    std::size_t stack_prefaulted_bytes = 0;
    /// Each refused step and why ("sched_fifo: Operation not permitted; ..."); empty if none.
    std::string refused;
};

/// The system calls used; each returns 0 or an errno value.
struct RealtimeCalls {
    int (*set_fifo)(int priority_offset);
    int (*pin_to_cpu)(int cpu);
    int (*set_timer_slack_ns)(unsigned long ns);
    int (*lock_all_memory)();
};

/// The real ones (pthread_setschedparam, pthread_setaffinity_np, prctl, mlockall).
const RealtimeCalls& system_realtime_calls();

/// Applies `request` to the calling thread. Never throws for a refusal.
RealtimeGrant make_this_thread_realtime(const RealtimeRequest& request,
                                        const RealtimeCalls& calls = system_realtime_calls());

/// Pins the calling thread to `cpu` (0 or an errno); for the thread that must stay off the
/// loop's CPU.
int pin_this_thread(int cpu);

/// The CPU the calling thread runs on now (-1 if unknown). Not a system call on x86-64 Linux
/// (vDSO), so the loop can call it per tick.
int current_cpu();

}  // namespace sandtin::haptics
