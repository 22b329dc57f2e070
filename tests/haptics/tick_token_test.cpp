// The tick token's protocol, with the two threads' steps interleaved by hand: the orders that a
// real race produces only rarely (the CI failure this token fixes) are played here every time.

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "haptics/tick_token.hpp"

namespace sandtin::haptics {
namespace {

TEST(TickToken, StartsAtTickZeroUnownedAndRunning) {
    TickToken token;
    const TickToken::Seen s = token.load();
    EXPECT_EQ(s.tick(), 0u);
    EXPECT_FALSE(s.owned());
    EXPECT_FALSE(s.finished());
}

TEST(TickToken, EachTickIsClaimedOnceAndHandedOn) {
    TickToken token;
    const TickToken::Seen primary = token.load();
    const TickToken::Seen backup = token.load();  // both saw tick 0 before either claimed it
    ASSERT_TRUE(token.try_claim(primary));
    EXPECT_TRUE(token.load().owned());
    EXPECT_FALSE(token.try_claim(backup));        // too late: the primary holds it
    EXPECT_FALSE(token.try_claim(token.load()));  // an owned token is never claimed
    token.release(primary.tick(), false);
    EXPECT_FALSE(token.try_claim(backup));  // its tick has been run: the word moved on
    const TickToken::Seen next = token.load();
    EXPECT_EQ(next.tick(), 1u);
    EXPECT_FALSE(next.owned());
    EXPECT_TRUE(token.try_claim(next));
}

// The CI failure: the backup looked at the loop's state, then the primary ran the last tick and
// ended the loop, then the backup read the tick number. With the end in the same word, whatever
// the backup read afterwards says the loop is over, and what it read before cannot be claimed.
TEST(TickToken, ALoopEndedBetweenTwoLooksCannotBeClaimedPast) {
    TickToken token;
    for (std::uint64_t t = 0; t < 5; ++t) {
        const TickToken::Seen s = token.load();
        ASSERT_TRUE(token.try_claim(s));
        token.release(t, false);
    }
    const TickToken::Seen backup_before = token.load();  // tick 5, running
    const TickToken::Seen primary = token.load();
    ASSERT_TRUE(token.try_claim(primary));
    token.release(primary.tick(), true);  // tick 5 found the device gone: the last
    const TickToken::Seen backup_after = token.load();
    EXPECT_TRUE(backup_after.finished());
    EXPECT_FALSE(token.try_claim(backup_before));
    EXPECT_FALSE(token.try_claim(backup_after));
    EXPECT_EQ(backup_after.tick(), 6u);  // the number of ticks run
    token.reset();
    EXPECT_TRUE(token.try_claim(token.load()));
}

// Two real threads claiming 20 000 ticks with no pause: every tick is run exactly once, and
// nothing runs after the last. (Under ThreadSanitizer this also checks the ordering.)
TEST(TickToken, TwoThreadsRacingRunEveryTickOnceAndNothingPastTheEnd) {
    constexpr std::uint64_t kLast = 20'000;
    TickToken token;
    std::vector<int> runs(kLast + 2, 0);
    auto worker = [&] {
        for (;;) {
            const TickToken::Seen s = token.load();
            if (s.finished()) return;
            if (!token.try_claim(s)) continue;
            ++runs[s.tick()];  // only the claimant touches this tick's slot
            token.release(s.tick(), s.tick() == kLast);
        }
    };
    std::thread a(worker);
    std::thread b(worker);
    a.join();
    b.join();
    for (std::uint64_t t = 0; t <= kLast; ++t)
        ASSERT_EQ(runs[t], 1) << t;
    EXPECT_EQ(runs[kLast + 1], 0);
    EXPECT_EQ(token.load().tick(), kLast + 1);
}

}  // namespace
}  // namespace sandtin::haptics
