// The real-time set-up asks for each step with the right arguments and, when the system
// refuses, reports each refusal and carries on; pinning to a CPU that does not exist is a
// refusal, not a crash. No test calls the real mlockall (it would lock the whole test process).

#include <gtest/gtest.h>

#include <sched.h>

#include <cerrno>
#include <thread>

#include "haptics/realtime_thread.hpp"

namespace sandtin::haptics {
namespace {

struct Seen {
    int fifo_offset = -100;
    int cpu = -100;
    unsigned long slack = 0;
    int locks = 0;
};
Seen seen;
int error_to_return = 0;

int fake_fifo(int offset) {
    seen.fifo_offset = offset;
    return error_to_return;
}
int fake_pin(int cpu) {
    seen.cpu = cpu;
    return error_to_return;
}
int fake_slack(unsigned long ns) {
    seen.slack = ns;
    return error_to_return;
}
int fake_lock() {
    ++seen.locks;
    return error_to_return;
}
const RealtimeCalls kFake{fake_fifo, fake_pin, fake_slack, fake_lock};

RealtimeRequest everything() {
    RealtimeRequest r;
    r.fifo = true;
    r.fifo_priority_offset = 7;
    r.cpu = 1;
    r.timer_slack = true;
    r.lock_memory = true;
    r.prefault_stack_bytes = 64 * 1024;
    return r;
}

TEST(RealtimeThread, AsksForEachStepAndReportsWhatWasGranted) {
    seen = {};
    error_to_return = 0;
    const RealtimeGrant g = make_this_thread_realtime(everything(), kFake);
    EXPECT_EQ(seen.fifo_offset, 7);
    EXPECT_EQ(seen.cpu, 1);
    EXPECT_EQ(seen.slack, 1u);
    EXPECT_EQ(seen.locks, 1);
    EXPECT_TRUE(g.fifo);
    EXPECT_EQ(g.cpu, 1);
    EXPECT_TRUE(g.timer_slack);
    EXPECT_TRUE(g.memory_locked);
    EXPECT_EQ(g.stack_prefaulted_bytes, 64u * 1024);
    EXPECT_EQ(g.refused, "");
}

TEST(RealtimeThread, RefusalsAreReportedNotThrown) {
    seen = {};
    error_to_return = EPERM;
    RealtimeGrant g;
    EXPECT_NO_THROW(g = make_this_thread_realtime(everything(), kFake));
    EXPECT_FALSE(g.fifo);
    EXPECT_EQ(g.cpu, -1);
    EXPECT_FALSE(g.timer_slack);
    EXPECT_FALSE(g.memory_locked);
    EXPECT_EQ(g.stack_prefaulted_bytes, 64u * 1024);  // needs no permission
    for (const char* step : {"mlockall", "cpu affinity", "timer slack", "sched_fifo"})
        EXPECT_NE(g.refused.find(std::string(step) + ": Operation not permitted"),
                  std::string::npos)
            << g.refused;
    error_to_return = 0;
}

TEST(RealtimeThread, StepsNotRequestedAreNotAttempted) {
    seen = {};
    error_to_return = EPERM;
    RealtimeRequest none;
    none.fifo = false;
    none.cpu = -1;
    none.timer_slack = false;
    none.lock_memory = false;
    none.prefault_stack_bytes = 0;
    const RealtimeGrant g = make_this_thread_realtime(none, kFake);
    EXPECT_EQ(seen.fifo_offset, -100);
    EXPECT_EQ(seen.cpu, -100);
    EXPECT_EQ(seen.locks, 0);
    EXPECT_EQ(g.refused, "");
    error_to_return = 0;
}

TEST(RealtimeThread, RealPinningToACpuThatDoesNotExistIsARefusal) {
    // On a thread of its own, so the test runner's thread keeps its affinity.
    // A CPU this process may run on (a container's cpuset need not include CPU 0).
    cpu_set_t allowed;
    ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
    int usable = 0;
    while (!CPU_ISSET(usable, &allowed))
        ++usable;
    RealtimeGrant bad, good;
    int cpu_after = -2;
    std::thread t([&] {
        RealtimeRequest r;
        r.fifo = false;
        r.cpu = 100000;
        bad = make_this_thread_realtime(r);
        r.cpu = usable;
        good = make_this_thread_realtime(r);
        cpu_after = current_cpu();
    });
    t.join();
    EXPECT_EQ(bad.cpu, -1);
    EXPECT_NE(bad.refused.find("cpu affinity"), std::string::npos);
    EXPECT_EQ(good.cpu, usable);
    EXPECT_EQ(cpu_after, usable);
    EXPECT_EQ(pin_this_thread(-1), EINVAL);
}

}  // namespace
}  // namespace sandtin::haptics
