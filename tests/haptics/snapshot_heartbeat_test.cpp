// The heartbeat (snapshot_heartbeat.hpp) against a running force loop: while held, the loop's
// snapshot never goes stale and the force stays at the model's value; released, it goes stale
// and fades to zero with no further republication; held again, the last snapshot comes back.
// Oracle for the force: the model's 800 N/m x (4 mm immersion + 0.625 mm offset) = 3.7 N on
// flat sand (force_model.hpp), as in force_loop_test.cpp. The only timing assumed is that a
// thread asked to wake every 10 ms does so within the 300 ms staleness limit.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "flat_snapshot.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/snapshot_heartbeat.hpp"

namespace sandtin::haptics {
namespace {

using namespace std::chrono_literals;

// The pen held still 4 mm deep in the sand, for as long as the loop runs.
class StillPen final : public HapticDevice {
  public:
    void open() override {}
    ReadStatus read(DeviceState& state) override {
        state = {{0.5, 0.5, -0.004}, 0, 0, true};
        return ReadStatus::Ok;
    }
    void write_force(const ForceCommand&) override {}
    void close() override {}
    double max_force() const override { return 10.0; }
    std::string name() const override { return "still pen"; }
};

ForceLoopConfig test_config() {
    ForceLoopConfig config;
    config.try_realtime = false;
    config.renderer.stale_after_ns = 300'000'000;
    config.renderer.ramp_ns = 20'000'000;
    return config;
}

// Polls the loop until `done(latest)` or 10 s pass; returns whether `done` came true.
template <class Done>
bool poll_until(ForceLoop& loop, Done done) {
    const auto give_up = std::chrono::steady_clock::now() + 10s;
    TickRecord latest;
    while (std::chrono::steady_clock::now() < give_up) {
        if (loop.poll(latest) && done(latest)) return true;
        std::this_thread::sleep_for(1ms);
    }
    return false;
}

TEST(SnapshotHeartbeat, HeldSnapshotStaysFreshAndReleasedOneFades) {
    StillPen pen;
    ForceLoop loop(pen, test_config());
    SnapshotHeartbeat heartbeat(loop, 10ms);
    heartbeat.publish(test::flat_snapshot());
    heartbeat.hold();
    EXPECT_TRUE(heartbeat.held());
    loop.start();
    ASSERT_TRUE(poll_until(loop, [](const TickRecord& t) {
        return !t.stale && std::abs(length(t.force) - 3.7) < 1e-9;
    }));

    // Held for 1.2 s, four staleness limits: every tick fresh, at full force.
    const auto held_until = std::chrono::steady_clock::now() + 1200ms;
    std::uint64_t ticks_seen = 0;
    TickRecord latest;
    while (std::chrono::steady_clock::now() < held_until) {
        if (loop.poll(latest)) {
            ++ticks_seen;
            ASSERT_FALSE(latest.stale) << "tick " << latest.tick;
            ASSERT_NEAR(length(latest.force), 3.7, 1e-9) << "tick " << latest.tick;
        }
        std::this_thread::sleep_for(1ms);
    }
    EXPECT_GT(ticks_seen, 0u);
    // Fresh over four staleness limits needs at least four publications after the first.
    EXPECT_GE(heartbeat.republished(), 4u);

    // Released: nothing more is republished, and the force fades to exactly zero.
    heartbeat.release();
    EXPECT_FALSE(heartbeat.held());
    const std::uint64_t at_release = heartbeat.republished();
    ASSERT_TRUE(poll_until(loop, [](const TickRecord& t) { return t.stale; }));
    ASSERT_TRUE(poll_until(loop, [](const TickRecord& t) { return length(t.force) == 0.0; }));
    EXPECT_EQ(heartbeat.republished(), at_release);

    // Held again, without a new snapshot: the last one is republished and the force returns.
    heartbeat.hold();
    ASSERT_TRUE(poll_until(loop, [](const TickRecord& t) {
        return !t.stale && std::abs(length(t.force) - 3.7) < 1e-9;
    }));
    EXPECT_GT(heartbeat.republished(), at_release);
    loop.stop();
}

TEST(SnapshotHeartbeat, HoldingWithoutASnapshotPublishesNothing) {
    StillPen pen;
    ForceLoop loop(pen, test_config());
    {
        SnapshotHeartbeat heartbeat(loop, 1ms);
        heartbeat.hold();
        loop.start();
        ASSERT_TRUE(poll_until(loop, [](const TickRecord& t) { return t.tick >= 50; }));
        EXPECT_EQ(heartbeat.republished(), 0u);
    }  // destroyed while held: joins its thread
    loop.stop();
    EXPECT_EQ(loop.report().snapshots_taken, 0u);
}

TEST(SnapshotHeartbeat, RejectsANonPositivePeriod) {
    StillPen pen;
    ForceLoop loop(pen, test_config());
    EXPECT_THROW(SnapshotHeartbeat(loop, 0ns), std::invalid_argument);
    EXPECT_THROW(SnapshotHeartbeat(loop, -1ms), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
