// GapStats on synthetic clock reads: gaps above the threshold are counted, summed and bucketed;
// the time between bursts (a sleep) is never a gap. And the probe itself runs briefly,
// accounting for its own spinning time.

#include <gtest/gtest.h>

#include "haptics/diagnostics/spin_probe.hpp"

namespace sandtin::haptics {
namespace {

TEST(SpinProbe, CountsSumsAndBucketsGapsAboveTheThreshold) {
    GapStats g(20'000);
    g.begin(0);
    std::int64_t t = 0;
    for (const std::int64_t step :
         {100, 20'000, 20'001, 150'000, 700'000, 1'500'000, 3'000'000, 12'000'000, 99'999})
        g.read(t += step);
    EXPECT_EQ(g.gaps(), 7u);  // 20 000 is not above the threshold
    EXPECT_EQ(g.stolen_ns(),
              20'001 + 150'000 + 700'000 + 1'500'000 + 3'000'000 + 12'000'000 + 99'999);
    EXPECT_EQ(g.max_gap_ns(), 12'000'000);
    EXPECT_EQ(g.observed_ns(), t);
    const std::array<std::uint64_t, 6> expected{2, 1, 1, 1, 1, 1};
    EXPECT_EQ(g.bucket_counts(), expected);
    // 99 999 ns sits in the first bucket: [threshold, 100 us).
    GapStats h(20'000);
    h.begin(0);
    h.read(99'999);
    h.read(99'999 + 100'000);
    EXPECT_EQ(h.bucket_counts()[0], 1u);
    EXPECT_EQ(h.bucket_counts()[1], 1u);
}

TEST(SpinProbe, TheSleepBetweenBurstsIsNotAGap) {
    GapStats g(20'000);
    g.begin(0);
    g.read(1'000);
    g.read(2'000);
    g.begin(50'000'000);  // slept 48 ms
    g.read(50'001'000);
    EXPECT_EQ(g.gaps(), 0u);
    EXPECT_EQ(g.max_gap_ns(), 1'000);
    EXPECT_EQ(g.observed_ns(), 3'000);
    // A read without begin starts a burst.
    GapStats h(20'000);
    h.read(5'000'000);
    h.read(5'001'000);
    EXPECT_EQ(h.observed_ns(), 1'000);
}

TEST(SpinProbe, RunsAndAccountsItsSpinningTime) {
    SpinProbeOptions o;
    o.seconds = 0.05;
    o.burst_ns = 5'000'000;
    o.sleep_ns = 5'000'000;
    o.realtime.fifo = false;
    const SpinProbeResult r = run_spin_probe(o);
    // About half of 50 ms spinning; bounds loose enough for a loaded machine.
    EXPECT_GT(r.gaps.observed_ns(), 5'000'000);
    EXPECT_LE(r.gaps.observed_ns(), 60'000'000);
    EXPECT_LE(r.gaps.stolen_ns(), r.gaps.observed_ns());
    EXPECT_GE(r.during.voluntary_switches, 1);  // it slept between bursts
}

TEST(SpinProbe, RejectsBadOptions) {
    SpinProbeOptions o;
    o.seconds = 0.0;
    EXPECT_THROW(run_spin_probe(o), std::invalid_argument);
    o.seconds = 1.0;
    o.burst_ns = 0;
    EXPECT_THROW(run_spin_probe(o), std::invalid_argument);
    EXPECT_THROW(GapStats(0), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
