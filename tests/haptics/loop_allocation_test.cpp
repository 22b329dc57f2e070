// The loop thread never allocates while it ticks: this executable replaces the global
// operator new with one that counts per thread, and a device wrapper (whose read() runs on the
// loop thread) notes the count at every tick. Between its first and last tick no loop thread's
// count may move, while the simulation side publishes snapshots and polls ticks, and the loop
// records every tick and its diagnostics keep late-tick phases.
// Its own executable, because replacing operator new is global to the program.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <new>
#include <thread>

#include "haptics/diagnostics/loop_diagnostics.hpp"
#include "haptics/force_loop.hpp"
#include "haptics/simulated_device.hpp"

namespace {
thread_local std::uint64_t allocations = 0;
// The count at this thread's previous device read; "none" before its first.
constexpr std::uint64_t kNone = ~std::uint64_t{0};
thread_local std::uint64_t seen_at_last_read = kNone;
}  // namespace

void* operator new(std::size_t size) {
    ++allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace sandtin::haptics {
namespace {

class CountingDevice final : public HapticDevice {
  public:
    explicit CountingDevice(SimulatedDevice& inner) : inner_(inner) {}
    void open() override { inner_.open(); }
    ReadStatus read(DeviceState& state) override {
        // Between two reads on the same thread lie a whole tick and the wait for the next:
        // count what that thread allocated there. (With a backup thread the reads alternate
        // between two threads; each keeps its own count.)
        if (seen_at_last_read != kNone) during_ += allocations - seen_at_last_read;
        seen_at_last_read = allocations;
        ++reads_;
        return inner_.read(state);
    }
    void write_force(const ForceCommand& command) override { inner_.write_force(command); }
    void close() override { inner_.close(); }
    double max_force() const override { return inner_.max_force(); }
    std::string name() const override { return "counting " + inner_.name(); }

    std::uint64_t reads() const { return reads_; }
    std::uint64_t allocations_during_ticks() const { return during_; }

  private:
    SimulatedDevice& inner_;
    std::uint64_t reads_ = 0;
    std::uint64_t during_ = 0;
};

void check_ticks_never_allocate(bool backup) {
    StrokeTrajectorySpec spec;
    spec.dwell = 0.05;
    spec.start_x = 0.45;
    spec.end_x = 0.55;
    const Trajectory trajectory = make_stroke_trajectory(spec);
    SimulatedDevice inner = SimulatedDevice::replay(trajectory);
    CountingDevice device(inner);
    ForceLoopConfig config;
    config.rate_hz = 4000.0;
    config.spin_ns = 50'000;
    config.try_realtime = false;
    config.record_capacity = trajectory.samples.size();
    config.backup_thread = backup;
    config.backup_margin_ns = 0;  // it races the primary for every tick
    // Every tick may be "late" here.
    LoopDiagnostics diagnostics(config, trajectory.samples.size());
    ForceLoop loop(device, config, &diagnostics);
    HapticSnapshot s;
    s.control_count = 3;
    s.control[0] = {0.45, 0.5};
    s.control[1] = {0.55, 0.45};
    s.control[2] = {0.55, 0.55};
    s.centre = {0.5, 0.5};
    loop.start();
    TickRecord latest;
    std::uint64_t polled = 0;
    while (loop.running()) {
        loop.publish(s);
        if (loop.poll(latest)) ++polled;
        std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    loop.stop();
    ASSERT_EQ(device.reads(), trajectory.samples.size() + 1);  // the last read finds it lost
    EXPECT_EQ(device.allocations_during_ticks(), 0u);
    EXPECT_GT(polled, 0u);
    EXPECT_EQ(loop.records().size(), trajectory.samples.size());
    EXPECT_GT(loop.report().snapshots_taken, 0u);
}

TEST(ForceLoopAllocation, TicksNeverAllocate) {
    check_ticks_never_allocate(false);
}

TEST(ForceLoopAllocation, TicksNeverAllocateWithABackupThread) {
    check_ticks_never_allocate(true);
}

TEST(ForceLoopAllocation, TheCounterSeesAllocations) {
    // The oracle itself: an allocation on this thread moves the counter.
    const std::uint64_t before = allocations;
    auto p = std::make_unique<int>(3);
    EXPECT_EQ(allocations, before + 1);
    EXPECT_EQ(*p, 3);
}

}  // namespace
}  // namespace sandtin::haptics
