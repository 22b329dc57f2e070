// The /proc parsers on hand-written text, and the live readers against an independent effect
// (touching fresh pages must count minor faults).

#include <gtest/gtest.h>
#include <sys/mman.h>

#include "haptics/diagnostics/os_counters.hpp"

namespace sandtin::haptics {
namespace {

TEST(OsCounters, ParsesSchedstat) {
    const auto s = parse_schedstat("2934393095 451917 10006\n");
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(s->cpu_ns, 2934393095);
    EXPECT_EQ(s->run_delay_ns, 451917);
    EXPECT_EQ(s->slices, 10006);
    EXPECT_FALSE(parse_schedstat("12 34").has_value());
    EXPECT_FALSE(parse_schedstat("").has_value());
    EXPECT_FALSE(parse_schedstat("a b c").has_value());
}

TEST(OsCounters, ParsesStealPerCpu) {
    const char* text =
        "cpu  3593090 1856 232560 732149 9083 0 550 2157 0 0\n"
        "cpu0 1717166 1853 103882 457803 3425 0 108 1118 0 0\n"
        "cpu1 1875923 3 128677 274345 5658 0 441 1039 0 0\n"
        "intr 12345 0 1 2\n"
        "ctxt 987654\n";
    const auto steal = parse_cpu_steal_ns(text, 100);
    ASSERT_TRUE(steal.has_value());
    ASSERT_EQ(steal->size(), 2u);
    EXPECT_EQ((*steal)[0], 1118LL * 10'000'000);
    EXPECT_EQ((*steal)[1], 1039LL * 10'000'000);
    // A kernel without the steal column, no per-CPU lines, or a bad tick rate.
    EXPECT_FALSE(parse_cpu_steal_ns("cpu0 1 2 3 4 5 6 7\n", 100).has_value());
    EXPECT_FALSE(parse_cpu_steal_ns("cpu  1 2 3 4 5 6 7 8\n", 100).has_value());
    EXPECT_FALSE(parse_cpu_steal_ns(text, 0).has_value());
}

TEST(OsCounters, DifferenceKeepsUnknownFieldsUnknown) {
    ThreadCounters a, b;
    a.sched = {100, 40, 7};
    b.sched = {60, 10, 2};
    a.minor_faults = 9;
    b.minor_faults = 4;
    a.major_faults = 3;  // b.major_faults unknown
    const ThreadCounters d = difference(a, b);
    EXPECT_EQ(d.sched.cpu_ns, 40);
    EXPECT_EQ(d.sched.run_delay_ns, 30);
    EXPECT_EQ(d.sched.slices, 5);
    EXPECT_EQ(d.minor_faults, 5);
    EXPECT_EQ(d.major_faults, -1);
    EXPECT_EQ(d.voluntary_switches, -1);
}

TEST(OsCounters, CountsTheMinorFaultsOfFreshPages) {
    constexpr std::size_t kPages = 64;
    const std::size_t bytes = kPages * 4096;
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(p, MAP_FAILED);
    const ThreadCounters before = read_this_thread_counters();
    ASSERT_GE(before.minor_faults, 0);
    auto* bytes_p = static_cast<volatile char*>(p);
    for (std::size_t i = 0; i < bytes; i += 4096)
        bytes_p[i] = 1;
    const ThreadCounters d = difference(read_this_thread_counters(), before);
    munmap(p, bytes);
    // Each first write to an anonymous page is a minor fault (unless huge pages served it,
    // which needs an aligned 2 MiB region: this one is 256 KiB).
    EXPECT_GE(d.minor_faults, static_cast<std::int64_t>(kPages));
    EXPECT_EQ(d.major_faults, 0);
    EXPECT_GE(d.sched.cpu_ns, 0);
    EXPECT_GE(d.sched.slices, 0);
}

TEST(OsCounters, ReadsStealForEveryCpuOrNothing) {
    const auto steal = read_cpu_steal_ns();
    for (const std::int64_t s : steal)
        EXPECT_GE(s, 0);
}

}  // namespace
}  // namespace sandtin::haptics
