#include "haptics/realtime_thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cstring>

namespace sandtin::haptics {

namespace {

int real_set_fifo(int offset) {
    sched_param p{};
    p.sched_priority = sched_get_priority_min(SCHED_FIFO) + offset;
    return pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
}

int real_set_timer_slack(unsigned long ns) {
    return prctl(PR_SET_TIMERSLACK, ns, 0, 0, 0) == 0 ? 0 : errno;
}

int real_lock_all_memory() {
    return mlockall(MCL_CURRENT | MCL_FUTURE) == 0 ? 0 : errno;
}

void note(std::string& refused, const char* step, int error) {
    if (!refused.empty()) refused += "; ";
    refused += step;
    refused += ": ";
    refused += std::strerror(error);
}

// Writes one byte per page of `bytes` of fresh stack below the caller. Not inlined, so the
// frame is really allocated; the barrier keeps the stores.
[[gnu::noinline]] void touch_stack(std::size_t bytes) {
    auto* p = static_cast<volatile char*>(__builtin_alloca(bytes));
    for (std::size_t i = 0; i < bytes; i += 4096)
        p[i] = 0;
    asm volatile("" ::: "memory");
}

}  // namespace

int pin_this_thread(int cpu) {
    if (cpu < 0 || cpu >= CPU_SETSIZE) return EINVAL;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(cpu), &set);
    return pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

int current_cpu() {
    return sched_getcpu();
}

const RealtimeCalls& system_realtime_calls() {
    static const RealtimeCalls calls{real_set_fifo, pin_this_thread, real_set_timer_slack,
                                     real_lock_all_memory};
    return calls;
}

RealtimeGrant make_this_thread_realtime(const RealtimeRequest& request,
                                        const RealtimeCalls& calls) {
    RealtimeGrant g;
    if (request.lock_memory) {
        const int e = calls.lock_all_memory();
        g.memory_locked = e == 0;
        if (e != 0) note(g.refused, "mlockall", e);
    }
    if (request.cpu >= 0) {
        const int e = calls.pin_to_cpu(request.cpu);
        if (e == 0) {
            g.cpu = request.cpu;
        } else {
            note(g.refused, "cpu affinity", e);
        }
    }
    if (request.timer_slack) {
        const int e = calls.set_timer_slack_ns(1);
        g.timer_slack = e == 0;
        if (e != 0) note(g.refused, "timer slack", e);
    }
    if (request.fifo) {
        const int e = calls.set_fifo(request.fifo_priority_offset);
        g.fifo = e == 0;
        if (e != 0) note(g.refused, "sched_fifo", e);
    }
    if (request.prefault_stack_bytes > 0) {
        touch_stack(request.prefault_stack_bytes);
        g.stack_prefaulted_bytes = request.prefault_stack_bytes;
    }
    return g;
}

}  // namespace sandtin::haptics
