// JitterStats on synthetic tick timings: maxima, the late-tick threshold, the cause of each
// late tick (the largest phase), the bounded event list and the worst tick.

#include <gtest/gtest.h>

#include "haptics/diagnostics/loop_jitter.hpp"

namespace sandtin::haptics {
namespace {

TickPhases tick(std::uint64_t n, std::int64_t period, std::int64_t work, std::int64_t wake_late,
                std::int64_t gap, bool slept = true, std::int64_t lateness = 0) {
    TickPhases t;
    t.tick = n;
    t.start_ns = static_cast<std::int64_t>(n) * 1'000'000;
    t.period_ns = period;
    t.work_ns = work;
    t.slept = slept;
    t.wake_late_ns = wake_late;
    t.spin_gap_ns = gap;
    t.lateness_ns = lateness;
    return t;
}

TEST(LoopJitter, CauseIsTheLargestPhase) {
    EXPECT_EQ(late_cause(tick(1, 5'000'000, 4'000'000, 10'000, 100)), LateCause::Work);
    EXPECT_EQ(late_cause(tick(1, 5'000'000, 8'000, 4'000'000, 100)), LateCause::Wakeup);
    EXPECT_EQ(late_cause(tick(1, 5'000'000, 8'000, 10'000, 4'000'000)), LateCause::SpinGap);
    EXPECT_STREQ(to_string(LateCause::Work), "work");
    EXPECT_STREQ(to_string(LateCause::Wakeup), "wakeup");
    EXPECT_STREQ(to_string(LateCause::SpinGap), "spin_gap");
}

TEST(LoopJitter, MaximaLateTicksAndCauses) {
    JitterStats s(1'500'000, 8);
    s.add(tick(1, 1'000'000, 9'000, 40'000, 300));
    s.add(tick(2, 1'000'100, 12'000, 20'000, 60'000));                  // long spin gap, not late
    s.add(tick(3, 1'500'000, 9'000, 20'000, 300));                      // exactly the threshold
    s.add(tick(4, 6'000'000, 9'000, 5'300'000, 200, true, 5'000'000));  // woke late
    s.add(tick(5, 3'000'000, 9'000, 20'000, 2'000'000, true, 2'000'000));
    s.add(tick(6, 2'500'000, 1'900'000, 0, 400, false, 1'500'000));  // the previous body overran
    const JitterSummary j = s.summary();
    EXPECT_EQ(j.ticks, 6u);
    EXPECT_EQ(j.max_work_ns, 1'900'000);
    EXPECT_EQ(j.max_wake_late_ns, 5'300'000);
    EXPECT_EQ(j.max_spin_gap_ns, 2'000'000);
    EXPECT_EQ(j.late_ticks, 3u);  // 4, 5, 6; tick 3 is not above the threshold
    EXPECT_EQ(j.late_by_wakeup, 1u);
    EXPECT_EQ(j.late_by_spin_gap, 1u);
    EXPECT_EQ(j.late_by_work, 1u);
    EXPECT_EQ(j.wakes_after_deadline, 1u);  // only tick 4 woke past its deadline
    EXPECT_EQ(j.long_spin_gaps, 2u);        // 60 us and 2 ms
    EXPECT_EQ(j.long_spin_gap_total_ns, 2'060'000);
    EXPECT_EQ(j.worst.tick, 4u);
    EXPECT_EQ(j.late_ticks_not_kept, 0u);
    ASSERT_EQ(s.late_ticks().size(), 3u);
    EXPECT_EQ(s.late_ticks()[0].tick, 4u);
    EXPECT_EQ(s.late_ticks()[1].tick, 5u);
    EXPECT_EQ(s.late_ticks()[2].tick, 6u);
}

TEST(LoopJitter, KeepsOnlyTheFirstEventsAndNeverGrows) {
    JitterStats s(1'500'000, 2);
    const auto* data = s.late_ticks().data();
    for (std::uint64_t n = 1; n <= 5; ++n)
        s.add(tick(n, 2'000'000 + static_cast<std::int64_t>(n), 0, 600'000, 0));
    EXPECT_EQ(s.summary().late_ticks, 5u);
    EXPECT_EQ(s.summary().late_ticks_not_kept, 3u);
    ASSERT_EQ(s.late_ticks().size(), 2u);
    EXPECT_EQ(s.late_ticks()[1].tick, 2u);
    EXPECT_EQ(s.late_ticks().data(), data);  // no reallocation
    EXPECT_EQ(s.summary().worst.tick, 5u);
    s.clear();
    EXPECT_EQ(s.summary().ticks, 0u);
    EXPECT_TRUE(s.late_ticks().empty());
}

TEST(LoopJitter, RejectsANonPositiveThreshold) {
    EXPECT_THROW(JitterStats(0, 4), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
