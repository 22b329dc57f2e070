// The lock-free exchange: single-thread semantics, and a two-thread run in which every value
// the reader takes must be one the writer published whole (never torn) and never older than
// the previous one. Run under ThreadSanitizer (label `tsan`) this also checks the ordering.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <thread>

#include "haptics/haptic_snapshot.hpp"
#include "haptics/triple_buffer.hpp"

namespace sandtin::haptics {
namespace {

struct Block {
    std::uint64_t serial = 0;
    std::array<std::uint64_t, 32> words{};  // all equal to serial * 7
};

TEST(TripleBuffer, ReaderSeesOnlyTheLatestPublishedValue) {
    TripleBuffer<int> b(-1);
    EXPECT_FALSE(b.update());
    EXPECT_EQ(b.front(), -1);
    b.write(1);
    b.write(2);
    EXPECT_TRUE(b.update());
    EXPECT_EQ(b.front(), 2);
    EXPECT_FALSE(b.update());
    EXPECT_EQ(b.front(), 2);
    b.back() = 3;
    EXPECT_FALSE(b.update());  // not published yet
    b.publish();
    EXPECT_TRUE(b.update());
    EXPECT_EQ(b.front(), 3);
}

TEST(TripleBuffer, TwoThreadsNeverTearOrGoBack) {
    TripleBuffer<Block> b;
    constexpr std::uint64_t kCount = 200000;
    std::thread writer([&] {
        for (std::uint64_t i = 1; i <= kCount; ++i) {
            Block& slot = b.back();
            slot.serial = i;
            slot.words.fill(i * 7);
            b.publish();
        }
    });
    std::uint64_t last = 0;
    std::uint64_t taken = 0;
    while (last < kCount) {
        if (!b.update()) continue;
        const Block& v = b.front();
        ASSERT_GT(v.serial, last);
        for (std::uint64_t w : v.words)
            ASSERT_EQ(w, v.serial * 7);
        last = v.serial;
        ++taken;
    }
    writer.join();
    EXPECT_EQ(last, kCount);
    EXPECT_GE(taken, 1u);
}

TEST(TripleBuffer, CarriesSnapshots) {
    TripleBuffer<HapticSnapshot> b;
    HapticSnapshot s;
    s.sequence = 9;
    s.control_count = 3;
    s.control_height[2] = 0.25;
    b.write(s);
    ASSERT_TRUE(b.update());
    EXPECT_EQ(b.front().sequence, 9u);
    EXPECT_EQ(b.front().control_height[2], 0.25);
}

}  // namespace
}  // namespace sandtin::haptics
