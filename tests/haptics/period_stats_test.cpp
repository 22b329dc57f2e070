// Percentiles, maximum and overruns on known data (no clocks involved).

#include <gtest/gtest.h>

#include "haptics/period_stats.hpp"

namespace sandtin::haptics {
namespace {

TEST(PeriodStats, PercentilesOfKnownPeriods) {
    PeriodStats s(1'000'000);
    // 98 periods of 1.000 ms, one of 1.2 ms, one of 3.5 ms.
    for (int i = 0; i < 98; ++i)
        s.add(999'500);
    s.add(1'200'000);
    s.add(3'500'000);
    const PeriodSummary m = s.summary();
    EXPECT_EQ(m.count, 100u);
    EXPECT_NEAR(m.p50_ms, 1.0, 1e-9);    // bin [0.999, 1.000) ms, reported by its upper edge
    EXPECT_NEAR(m.p99_ms, 1.201, 1e-9);  // the 99th of 100 sorted samples is 1.2 ms
    EXPECT_NEAR(m.max_ms, 3.5, 1e-12);
    EXPECT_EQ(m.overruns, 2u);  // > 1.1 ms
    EXPECT_NEAR(m.mean_ms, (98 * 0.9995 + 1.2 + 3.5) / 100.0, 1e-9);
}

TEST(PeriodStats, HugePeriodsLandInTheOverflowBin) {
    PeriodStats s(250'000);
    s.add(5'000'000'000);
    s.add(-5);  // clock oddities count as zero
    const PeriodSummary m = s.summary();
    EXPECT_NEAR(m.max_ms, 5000.0, 1e-9);
    EXPECT_NEAR(m.p99_ms, 5000.0, 1e-9);
    EXPECT_EQ(m.overruns, 1u);
    s.clear();
    EXPECT_EQ(s.summary().count, 0u);
    EXPECT_THROW(PeriodStats(0), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
