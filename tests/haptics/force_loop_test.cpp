// The loop thread end to end with a simulated device: it stops by itself when the device is
// lost, renders exactly what the renderer computes offline from the same inputs, and stops
// cleanly on request. No assertion on timing.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <iostream>
#include <thread>

#include "flat_snapshot.hpp"
#include "haptics/diagnostics/loop_diagnostics.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/simulated_device.hpp"

namespace sandtin::haptics {
namespace {

// With `backup`, a second thread races the primary for every tick (margin 0: both are at the
// deadline), so ticks change hands often; the result must not depend on who ran which tick.
// Sets `major_faults` to those the primary loop thread took during its ticks.
void check_runs_to_the_end_like_the_offline_renderer(bool backup, std::int64_t& major_faults) {
    StrokeTrajectorySpec spec;
    spec.start_x = 0.5;
    spec.end_x = 0.5 + 1e-9;
    spec.dwell = 0.1;
    const Trajectory trajectory = make_stroke_trajectory(spec);
    SimulatedDevice device = SimulatedDevice::replay(trajectory);
    ForceLoopConfig config;
    config.rate_hz = 4000.0;  // fast, to keep the test short
    config.spin_ns = 50'000;
    config.record_capacity = trajectory.samples.size();
    config.renderer.stale_after_ns = 3'600'000'000'000;  // never stale in this test
    config.renderer.ramp_ns = 1'000'000;
    config.try_realtime = false;
    config.backup_thread = backup;
    config.backup_margin_ns = 0;
    LoopDiagnostics diagnostics(config);
    ForceLoop loop(device, config, &diagnostics);
    loop.publish(test::flat_snapshot(0.0));  // before start: the first tick takes it
    loop.start();
    while (loop.running())
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    loop.stop();

    const ForceLoopReport report = loop.report();
    const JitterSummary jitter = diagnostics.jitter();
    major_faults = diagnostics.during_ticks().major_faults;
    EXPECT_TRUE(report.device_lost);
    EXPECT_EQ(report.ticks, trajectory.samples.size());
    ASSERT_EQ(loop.records().size(), trajectory.samples.size());
    // One period per tick, counting the last one, whose read found the device gone.
    EXPECT_EQ(report.periods.count, trajectory.samples.size());
    EXPECT_EQ(report.snapshots_taken, 1u);
    // The phase timings cover the same ticks as the periods; kept late ticks are late.
    EXPECT_EQ(jitter.ticks, report.periods.count);
    EXPECT_FALSE(report.realtime_grant.fifo);
    EXPECT_FALSE(report.realtime);
    EXPECT_LE(diagnostics.late_ticks().size(), jitter.late_ticks);
    for (const TickPhases& t : diagnostics.late_ticks())
        EXPECT_GT(t.period_ns, 250'000 * 3 / 2);
    EXPECT_EQ(jitter.late_ticks,
              jitter.late_by_work + jitter.late_by_wakeup + jitter.late_by_spin_gap);
    EXPECT_GE(jitter.worst.period_ns, static_cast<std::int64_t>(report.periods.max_ms * 1e6) - 1);
    // measured: getrusage answers per thread
    EXPECT_GE(diagnostics.during_ticks().major_faults, 0);
    EXPECT_GT(loop.thread_id(), 0);
    // The device got one force per sample plus the final zero.
    ASSERT_EQ(device.forces().size(), trajectory.samples.size() + 1);
    EXPECT_EQ(device.forces().back(), (Vec3{}));

    // Offline: the same renderer over the same positions and times gives the same forces.
    ForceRenderer offline(loop.config().renderer);
    HapticSnapshot s = test::flat_snapshot(0.0);
    s.sequence = 1;
    // Published just before the first tick, as in the loop: with published_ns = 0 the offline
    // snapshot would count as stale once the machine has been up for stale_after_ns (an hour).
    ASSERT_FALSE(loop.records().empty());
    s.published_ns = loop.records().front().time_ns;
    double max_force = 0.0;
    for (std::size_t i = 0; i < loop.records().size(); ++i) {
        const TickRecord& r = loop.records()[i];
        EXPECT_EQ(r.device.position, trajectory.samples[i].position);
        const TickOutput o = offline.tick(r.device.position, r.time_ns, i == 0 ? &s : nullptr);
        EXPECT_EQ(o.force, r.force) << i;
        EXPECT_EQ(device.forces()[i], r.force) << i;
        max_force = std::max(max_force, length(r.force));
    }
    // 4 mm deep on flat sand: 800 (0.004 + 0.000625) = 3.7 N once blended and ramped in.
    EXPECT_NEAR(max_force, 3.7, 1e-9);
    // Every tick ran exactly once, in order, whichever thread ran it.
    for (std::size_t i = 0; i < loop.records().size(); ++i)
        EXPECT_EQ(loop.records()[i].tick, i);
    EXPECT_LE(report.ticks_by_backup, report.ticks);
    if (!backup) {
        EXPECT_EQ(report.ticks_by_backup, 0u);
    }
}

// The ticks do no I/O and touch only memory that exists before the first tick, so they take no
// major page fault. These tests do not ask for mlockall, though, so under the memory pressure
// of a parallel sanitizer run the kernel may evict a code page the ticks execute and read it
// back once: the machine's doing, seen once in a clean-clone TSan pass. A second run straight
// after finds that page resident; a loop that read files or touched swapped memory would fault
// again. So a run with faults is repeated once, and the repeat must have none.
void check_twice_if_the_first_run_faulted(bool backup) {
    std::int64_t faults = -1;
    check_runs_to_the_end_like_the_offline_renderer(backup, faults);
    if (faults == 0) return;
    std::cerr << "the first run took " << faults
              << " major page fault(s) during its ticks; running it again\n";
    faults = -1;
    check_runs_to_the_end_like_the_offline_renderer(backup, faults);
    EXPECT_EQ(faults, 0);
}

TEST(ForceLoop, RunsUntilTheTrajectoryEndsAndMatchesTheOfflineRenderer) {
    check_twice_if_the_first_run_faulted(false);
}

TEST(ForceLoop, WithABackupThreadEveryTickRunsOnceAndTheForcesAreTheSame) {
    check_twice_if_the_first_run_faulted(true);
}

// A device lost after `ticks` reads, counting every read and write that follows.
class CountingDevice final : public HapticDevice {
  public:
    explicit CountingDevice(int ticks) : ticks_(ticks) {}
    void open() override {}
    ReadStatus read(DeviceState& state) override {
        ++reads_;
        if (reads_ > ticks_) return ReadStatus::Lost;
        state = {{0.5, 0.5, -0.004}, 0, 0, true};
        return ReadStatus::Ok;
    }
    void write_force(const ForceCommand&) override { ++writes_; }
    void close() override {}
    double max_force() const override { return 10.0; }
    std::string name() const override { return "counting"; }
    int reads_ = 0;
    int writes_ = 0;

  private:
    int ticks_;
};

// The last tick (the read that finds the device gone) ends the loop for both threads. The
// thread that did not run it may be spinning on the token at that moment: it must see the end,
// not take the next tick number and read the lost device again. Short loops, many times, so
// the two threads meet at the last tick often.
TEST(ForceLoop, WithABackupThreadNoTickRunsAfterTheLast) {
    constexpr int kTicks = 8;
    constexpr int kRuns = 100;
    int extra_reads = 0;
    for (int run = 0; run < kRuns; ++run) {
        CountingDevice device(kTicks);
        ForceLoopConfig config;
        config.rate_hz = 4000.0;
        config.spin_ns = 50'000;
        config.try_realtime = false;
        config.backup_thread = true;
        config.backup_margin_ns = 0;
        ForceLoop loop(device, config);
        loop.start();
        while (loop.running())
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        loop.stop();
        EXPECT_EQ(loop.report().ticks, static_cast<std::uint64_t>(kTicks)) << run;
        extra_reads += device.reads_ - (kTicks + 1);
        // One force per tick and the final zero; no read or write after the device was lost.
        ASSERT_EQ(device.reads_, kTicks + 1) << "run " << run;
        ASSERT_EQ(device.writes_, kTicks + 1) << "run " << run;
    }
    EXPECT_EQ(extra_reads, 0);
}

TEST(ForceLoop, StopFadesTheForceOutInsteadOfDroppingIt) {
    // Pressed 4 mm into flat sand for a minute: a steady 3.7 N until we stop the loop.
    Trajectory t;
    t.samples.assign(60000, {{0.5, 0.5, -0.004}, 0});
    SimulatedDevice device = SimulatedDevice::replay(t);
    ForceLoopConfig config;
    config.try_realtime = false;
    config.renderer.ramp_ns = 1'000'000;
    config.renderer.stale_after_ns = 3'600'000'000'000;
    config.stop_ramp_ns = 50'000'000;  // 50 ticks
    ForceLoop loop(device, config);
    loop.publish(test::flat_snapshot(0.0));
    loop.start();
    TickRecord latest;
    while (!(loop.poll(latest) && latest.tick >= 100 && length(latest.force) > 3.6)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    loop.stop();
    const std::vector<Vec3>& f = device.forces();
    ASSERT_GT(f.size(), 60u);
    EXPECT_EQ(f.back(), (Vec3{}));
    // From the last full-force tick to the end: monotone, steps of 3.7 / 50 N, about 50 ticks.
    std::size_t last_full = f.size() - 1;
    while (last_full > 0 && std::abs(length(f[last_full]) - 3.7) > 1e-9)
        --last_full;
    EXPECT_GE(f.size() - 1 - last_full, 49u);
    EXPECT_LE(f.size() - 1 - last_full, 52u);
    for (std::size_t i = last_full + 1; i < f.size(); ++i) {
        EXPECT_LE(length(f[i]), length(f[i - 1]) + 1e-12) << i;
        EXPECT_LE(length(f[i - 1]) - length(f[i]), 3.7 / 50.0 + 1e-9) << i;
    }
}

// A device with no pose for its first ticks (a network device before the driver connects).
class LateDevice final : public HapticDevice {
  public:
    void open() override {}
    ReadStatus read(DeviceState& state) override {
        if (reads_ == 300) return ReadStatus::Lost;
        state = {};
        if (reads_++ >= 20) state = {{0.5, 0.5, -0.004}, 0, 0, true};
        return ReadStatus::Ok;
    }
    void write_force(const ForceCommand& c) override { forces_.push_back(c.force); }
    void close() override {}
    double max_force() const override { return 10.0; }
    std::string name() const override { return "late"; }
    std::vector<Vec3> forces_;

  private:
    int reads_ = 0;
};

TEST(ForceLoop, ASnapshotPublishedBeforeTheFirstPoseIsUsed) {
    LateDevice device;
    ForceLoopConfig config;
    config.rate_hz = 4000.0;
    config.spin_ns = 50'000;
    config.try_realtime = false;
    config.renderer.ramp_ns = 1'000'000;
    config.renderer.stale_after_ns = 3'600'000'000'000;
    ForceLoop loop(device, config);
    loop.publish(test::flat_snapshot(0.0));  // the only snapshot, taken while there is no pose
    loop.start();
    while (loop.running())
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    loop.stop();
    ASSERT_EQ(device.forces_.size(), 301u);   // 300 ticks and the final zero
    EXPECT_EQ(device.forces_[19], (Vec3{}));  // no pose, no force
    EXPECT_NEAR(length(device.forces_[299]), 3.7, 1e-9);
}

TEST(ForceLoop, StopsCleanlyOnRequestAndRejectsBadRates) {
    SimulatedDevice device = SimulatedDevice::spring({}, {0.5, 0.5, 1.0});
    ForceLoopConfig config;
    config.try_realtime = false;
    {
        ForceLoop loop(device, config);
        loop.start();
        EXPECT_THROW(loop.start(), std::logic_error);
        HapticSnapshot s = test::flat_snapshot(0.0);
        TickRecord latest;
        for (int i = 0; i < 20; ++i) {
            loop.publish(s);
            loop.poll(latest);
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        EXPECT_TRUE(loop.running());
        loop.stop();
        EXPECT_FALSE(loop.running());
        loop.stop();  // idempotent
        EXPECT_FALSE(loop.report().device_lost);
    }
    {
        ForceLoop loop(device, config);
        loop.start();
    }  // destructor stops it
    config.rate_hz = 4001.0;
    EXPECT_THROW(ForceLoop(device, config), std::invalid_argument);
    config.rate_hz = 0.0;
    EXPECT_THROW(ForceLoop(device, config), std::invalid_argument);
    config.rate_hz = 1000.0;
    config.spin_ns = 1'000'000;
    EXPECT_THROW(ForceLoop(device, config), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin::haptics
