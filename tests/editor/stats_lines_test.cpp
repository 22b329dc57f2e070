// The Stats window's timing lines (editor/app/stats_lines.hpp): bounded whatever the numbers,
// so the window made for the widest fits a machine however slow.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "stats_lines.hpp"

namespace sandtin::editor {
namespace {

TEST(StatsLines, EveryNumberFitsItsWidthWithThePrecisionItsSizeDeserves) {
    EXPECT_EQ(capped_number(0.0), "0.00");
    EXPECT_EQ(capped_number(0.421), "0.42");
    EXPECT_EQ(capped_number(12.344), "12.34");
    EXPECT_EQ(capped_number(99.996), "100.0");
    EXPECT_EQ(capped_number(123.44), "123.4");
    EXPECT_EQ(capped_number(9999.9), "10000");
    EXPECT_EQ(capped_number(99999.4), "99999");
    EXPECT_EQ(capped_number(99999.5), ">99999");
    EXPECT_EQ(capped_number(1e30), ">99999");
    EXPECT_EQ(capped_number(-1.0), "-");
    EXPECT_EQ(capped_number(std::numeric_limits<double>::quiet_NaN()), "-");
    EXPECT_EQ(capped_number(std::numeric_limits<double>::infinity()), "-");
    // Every magnitude, at every rounding boundary: never wider than promised.
    for (double v = 1e-6; v < 1e12; v *= 1.0007)
        ASSERT_LE(capped_number(v).size(), kCappedNumberChars) << v;
}

TEST(StatsLines, NoTimingLineIsLongerThanTheWidestWhateverTheTimes) {
    const auto widest = widest_stats_timing_lines();
    for (const double ms : {0.0, 0.004, 11.6, 86.2, 999.96, 9999.9, 1e5, 1e9}) {
        StageMedians m{ms, ms, ms, ms, ms, ms, ms};
        const auto lines = stats_timing_lines(m);
        for (std::size_t i = 0; i < lines.size(); ++i)
            EXPECT_LE(lines[i].size(), widest[i].size()) << ms << ": " << lines[i];
    }
    const auto slow = stats_timing_lines({9999.9, 1.5, 9999.9, 0.25, 0.0, 0.0, 9999.9});
    EXPECT_EQ(slow[0], "0.10 fps (10000 ms)");
    EXPECT_EQ(slow[1], "tool 1.50  physics 10000  mesh 0.25");
    EXPECT_EQ(slow[2], "upload 0.00  bake 0.00  render 10000 ms");
}

}  // namespace
}  // namespace sandtin::editor
