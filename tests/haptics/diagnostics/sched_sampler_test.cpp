// Attributing a window to the observer's samples (synthetic series), and the observer thread
// itself: it samples a live thread of this process, in time order.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include <unistd.h>

#include "haptics/diagnostics/sched_sampler.hpp"

namespace sandtin::haptics {
namespace {

SchedSample sample(std::int64_t t, std::int64_t run_delay, std::int64_t steal0,
                   std::int64_t steal1) {
    SchedSample s;
    s.read_start_ns = t - 10;
    s.time_ns = t;
    s.run_delay_ns = run_delay;
    s.steal_ns.fill(-1);
    s.steal_ns[0] = steal0;
    s.steal_ns[1] = steal1;
    return s;
}

const std::vector<SchedSample> kSeries = {
    sample(1000, 0, 0, 0),
    sample(2000, 5, 0, 0),
    sample(3000, 5, 0, 10'000),
    sample(4000, 700, 0, 30'000),
    sample(5000, 700, 20'000, 30'000),
};

TEST(SchedSampler, AttributesAWindowToTheBracketingSamples) {
    // [2500, 3500]: from the sample at 2000 to the one read from 3990.
    const WindowAttribution a = attribute_window(kSeries, 2500, 3500, 1);
    ASSERT_TRUE(a.covered);
    EXPECT_EQ(a.span_ns, 2000);
    EXPECT_EQ(a.run_delay_ns, 695);
    EXPECT_EQ(a.steal_on_cpu_ns, 30'000);
    EXPECT_EQ(a.steal_all_cpus_ns, 30'000);
    const WindowAttribution b = attribute_window(kSeries, 4000, 4500, 0);
    ASSERT_TRUE(b.covered);
    EXPECT_EQ(b.span_ns, 1000);
    EXPECT_EQ(b.run_delay_ns, 0);
    EXPECT_EQ(b.steal_on_cpu_ns, 20'000);
    // An unknown CPU still gets the total.
    const WindowAttribution c = attribute_window(kSeries, 4000, 4500, -1);
    EXPECT_EQ(c.steal_on_cpu_ns, 0);
    EXPECT_EQ(c.steal_all_cpus_ns, 20'000);
}

TEST(SchedSampler, ASampleReadDuringTheWindowDoesNotCloseIt) {
    // The sample stamped 3000 was read from 2990: it cannot bound a window ending at 2995.
    const WindowAttribution a = attribute_window(kSeries, 2100, 2995, 1);
    ASSERT_TRUE(a.covered);
    EXPECT_EQ(a.span_ns, 2000);  // 2000 .. 4000
}

TEST(SchedSampler, WindowsOutsideTheSeriesAreNotCovered) {
    EXPECT_FALSE(attribute_window(kSeries, 500, 1500, 0).covered);
    EXPECT_FALSE(attribute_window(kSeries, 4500, 5500, 0).covered);
    EXPECT_FALSE(attribute_window({}, 0, 1, 0).covered);
}

TEST(SchedSampler, ObservesALiveThreadInTimeOrder) {
    std::atomic<int> tid{0};
    std::atomic<bool> done{false};
    std::thread worker([&] {
        tid.store(static_cast<int>(gettid()));
        while (!done.load())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    while (tid.load() == 0)
        std::this_thread::yield();
    SchedSampler sampler(tid.load(), 1'000'000, 1000);
    sampler.start();
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    sampler.stop();
    sampler.stop();  // idempotent
    done.store(true);
    worker.join();
    ASSERT_TRUE(sampler.available());
    const auto& s = sampler.samples();
    ASSERT_GE(s.size(), 2u);
    for (std::size_t i = 0; i < s.size(); ++i) {
        EXPECT_LE(s[i].read_start_ns, s[i].time_ns);
        EXPECT_GE(s[i].run_delay_ns, 0);
        if (i > 0) {
            EXPECT_GE(s[i].read_start_ns, s[i - 1].time_ns);
            EXPECT_GE(s[i].run_delay_ns, s[i - 1].run_delay_ns);  // cumulative
        }
    }
}

TEST(SchedSampler, RejectsBadArguments) {
    EXPECT_THROW(SchedSampler(0, 1'000'000, 10), std::invalid_argument);
    EXPECT_THROW(SchedSampler(1, 0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
