#pragma once
// The haptic thread: ticks at a fixed rate (default 1 kHz, up to 4 kHz) on the monotonic
// clock, waiting for each deadline by sleeping until shortly before it and spinning the rest
// (the OS wakes sleepers late by tens to hundreds of microseconds; spinning absorbs that).
//
// Each tick: read the device; take the newest snapshot the simulation published (lock-free
// triple buffer, never a mutex); render the force (force_renderer.hpp); write it; publish the
// device state and force back to the simulation (a second triple buffer); record the period.
//
// It stops cleanly when stop() is called (or on destruction): the force fades linearly to zero
// over `stop_ramp_ns` first, so quitting never jerks the user's hand. It stops by itself when
// the device is lost. The last force it writes is zero. A late tick is not made up: the schedule
// restarts from now, so a stall never causes a burst of catch-up ticks.
//
// The tick path makes no system call other than reading the clock and the absolute-time sleep
// (clock_nanosleep TIMER_ABSTIME), and never allocates (records and statistics are
// preallocated). Each tick's phases (how long the sleep overslept, the longest gap in the spin,
// the previous tick's work; loop_observer.hpp) go to an observer when one is attached: the OS
// jitter diagnostics (diagnostics/loop_diagnostics.hpp) attribute late ticks with them.

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "haptics/force_renderer.hpp"
#include "haptics/haptic_device.hpp"
#include "haptics/haptic_snapshot.hpp"
#include "haptics/loop_observer.hpp"
#include "haptics/period_stats.hpp"
#include "haptics/realtime_thread.hpp"
#include "haptics/tick_token.hpp"
#include "haptics/triple_buffer.hpp"

namespace sandtin::haptics {

inline constexpr double kMaxLoopRateHz = 4000.0;

struct ForceLoopConfig {
    double rate_hz = 1000.0;  ///< (0, 4000]
    /// Spin this long before each deadline instead of sleeping (ns). Must be < one period.
    std::int64_t spin_ns = 300'000;
    ForceRendererConfig renderer;  ///< its rate_hz is overwritten with rate_hz
    /// Keep a record of every tick (up to this many; preallocated, so recording never
    /// allocates in the loop). 0 = no record.
    std::size_t record_capacity = 0;
    /// On stop(), fade the force to zero over this long before the thread ends (ns; 0 = at
    /// once). 50 ms takes 10 N down in steps of 0.2 N at 1 kHz.
    std::int64_t stop_ramp_ns = 50'000'000;
    /// Ask for SCHED_FIFO; refused without privileges, which is reported, not an error.
    bool try_realtime = true;
    /// The rest of the thread's real-time set-up (realtime_thread.hpp); its `fifo` is
    /// overwritten with try_realtime. Defaults: timer slack 1 ns and a pre-faulted stack; no
    /// pinning and no mlockall (process-wide: the caller opts in).
    RealtimeRequest realtime;
    /// Sleep with clock_nanosleep(TIMER_ABSTIME) (true) or std::this_thread::sleep_until,
    /// which sleeps a relative interval computed from a clock read (false; for comparison).
    bool absolute_sleep = true;
    /// A second, backup thread that sleeps until `backup_margin_ns` after each deadline and
    /// takes the tick if the primary has not started it (its wake-up came late). Ticks are
    /// handed between the two through one atomic token, so exactly one runs each tick and
    /// the device is never used by both at once. For machines whose timer wake-ups are
    /// sometimes late by milliseconds (virtual machines): two CPUs are rarely late together.
    /// The backup costs one wake-up per tick on another CPU. Requires a device that may be
    /// driven from either thread (both built-in devices can).
    bool backup_thread = false;
    std::int64_t backup_margin_ns = 250'000;
    /// Pin the backup to this CPU (-1: not pinned). It only helps when it cannot share the
    /// primary's CPU, so pin both (realtime.cpu and this) to different CPUs.
    int backup_cpu = -1;
};

/// The period of a loop with `config` (ns). Throws std::invalid_argument, as ForceLoop's
/// constructor does, for a rate outside (0, 4000] Hz, a spin >= one period or a negative ramp.
std::int64_t loop_period_ns(const ForceLoopConfig& config);

/// One tick, as the simulation sees it and as recordings store it.
struct TickRecord {
    std::uint64_t tick = 0;
    std::int64_t time_ns = 0;  ///< monotonic clock at the start of the tick
    DeviceState device;
    Vec3 force;  ///< N, as written to the device
    bool contact = false;
    bool stale = false;
    std::uint64_t snapshot_sequence = 0;
};

struct ForceLoopReport {
    PeriodSummary periods;
    std::uint64_t ticks = 0;
    bool device_lost = false;
    bool realtime = false;        ///< SCHED_FIFO was granted
    double max_force = 0.0;       ///< N, largest |F| written
    double max_force_jump = 0.0;  ///< N, largest |F_t - F_(t-1)| between consecutive ticks
    std::uint64_t force_jumps_over_half_newton = 0;
    std::uint64_t stale_ticks = 0;
    std::uint64_t snapshots_taken = 0;
    RealtimeGrant realtime_grant;       ///< what the thread's set-up got
    std::uint64_t ticks_by_backup = 0;  ///< ticks the backup thread ran (backup_thread)
};

class ForceLoop {
  public:
    /// Throws std::invalid_argument for a rate outside (0, 4000] Hz or a spin >= one period.
    /// `observer`, when given, sees every run (loop_observer.hpp); it must outlive the loop.
    ForceLoop(HapticDevice& device, ForceLoopConfig config, LoopObserver* observer = nullptr);
    ~ForceLoop();
    ForceLoop(const ForceLoop&) = delete;
    ForceLoop& operator=(const ForceLoop&) = delete;

    /// Opens the device (its exceptions propagate) and starts the thread.
    void start();
    /// Stops the thread (if running), writes a zero force, closes the device. Idempotent.
    void stop();
    /// False once the thread has ended by itself (device lost) or after stop().
    bool running() const { return running_.load(std::memory_order_acquire); }

    // ---- Simulation thread (a single producer/consumer) ----
    /// Publishes a snapshot: sets its sequence and publication time, wait-free.
    void publish(HapticSnapshot snapshot);
    /// The newest tick the loop has published back, if there is a newer one than last time.
    bool poll(TickRecord& latest);

    // ---- After stop() ----
    ForceLoopReport report() const;
    const std::vector<TickRecord>& records() const { return records_; }

    /// The loop thread's kernel thread id once it runs (0 before), for observers.
    int thread_id() const { return thread_id_.load(std::memory_order_acquire); }
    const ForceLoopConfig& config() const { return config_; }

  private:
    struct TickState;

    void run();
    void wait_and_tick(TickState& s, bool backup);
    /// One tick, by the holder of the token; false when the loop ends (after a zero force).
    bool run_tick(TickState& s, std::uint64_t tick, std::int64_t now, std::int64_t deadline,
                  TickPhases phases, bool backup);

    HapticDevice& device_;
    ForceLoopConfig config_;
    LoopObserver* observer_;
    std::int64_t period_ns_;
    TripleBuffer<HapticSnapshot> snapshots_;
    TripleBuffer<TickRecord> ticks_;
    std::uint64_t next_sequence_ = 1;  // simulation thread
    std::atomic<bool> stop_requested_{false};
    std::atomic<bool> running_{false};
    std::atomic<int> thread_id_{0};
    // The tick schedule between the primary and the backup thread: token_ names the next tick
    // (and whether the loop is over); deadline_ is that tick's deadline, written before the
    // token is released.
    TickToken token_;
    std::atomic<std::int64_t> deadline_{0};
    std::thread thread_;
    bool opened_ = false;
    // Owned by the loop thread while it runs; read after join.
    PeriodStats periods_;
    std::vector<TickRecord> records_;
    ForceLoopReport report_;
};

}  // namespace sandtin::haptics
