#include "haptics/force_loop.hpp"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sandtin::haptics {

std::int64_t monotonic_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

namespace {

std::int64_t checked_period(const ForceLoopConfig& c) {
    if (!(c.rate_hz > 0.0) || !(c.rate_hz <= kMaxLoopRateHz)) {
        throw std::invalid_argument("force loop: rate_hz must be in (0, 4000], got " +
                                    std::to_string(c.rate_hz));
    }
    const auto period = static_cast<std::int64_t>(std::llround(1e9 / c.rate_hz));
    if (c.spin_ns < 0 || c.spin_ns >= period)
        throw std::invalid_argument("force loop: spin_ns must be in [0, period)");
    if (c.stop_ramp_ns < 0) throw std::invalid_argument("force loop: stop_ramp_ns must be >= 0");
    return period;
}

ForceLoopConfig with_rate(ForceLoopConfig c) {
    c.renderer.rate_hz = c.rate_hz;
    c.realtime.fifo = c.try_realtime;
    return c;
}

void sleep_until_ns(std::int64_t t, bool absolute) {
    if (!absolute) {
        std::this_thread::sleep_until(
            std::chrono::steady_clock::time_point(std::chrono::nanoseconds(t)));
        return;
    }
    // steady_clock is CLOCK_MONOTONIC in libstdc++ and libc++ on Linux, so the deadlines are
    // in the same time base. EINTR (a signal) just returns early; the spin covers it.
    const timespec ts{static_cast<time_t>(t / 1'000'000'000), static_cast<long>(t % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace

ForceLoop::ForceLoop(HapticDevice& device, ForceLoopConfig config)
    : device_(device),
      config_(with_rate(config)),
      period_ns_(checked_period(config_)),
      periods_(period_ns_),
      jitter_(period_ns_ * 3 / 2, config_.late_tick_capacity) {
    ForceRenderer check(config_.renderer);  // validates the renderer settings now
    records_.reserve(config_.record_capacity);
}

ForceLoop::~ForceLoop() {
    stop();
}

void ForceLoop::start() {
    if (thread_.joinable() || opened_) throw std::logic_error("force loop: already started");
    device_.open();
    opened_ = true;
    if (config_.hold_cpu_wake_latency) wake_latency_ = std::make_unique<CpuWakeLatencyHold>(0);
    stop_requested_.store(false);
    running_.store(true, std::memory_order_release);
    thread_ = std::thread([this] { run(); });
}

void ForceLoop::stop() {
    stop_requested_.store(true, std::memory_order_release);
    if (thread_.joinable()) thread_.join();
    running_.store(false, std::memory_order_release);
    if (wake_latency_) {
        report_.cpu_wake_latency_held = wake_latency_->held();
        report_.cpu_wake_latency_error = wake_latency_->error();
        wake_latency_.reset();
    }
    if (opened_) {
        device_.close();
        opened_ = false;
    }
}

void ForceLoop::publish(HapticSnapshot snapshot) {
    snapshot.sequence = next_sequence_++;
    snapshot.published_ns = monotonic_ns();
    snapshots_.write(snapshot);
}

bool ForceLoop::poll(TickRecord& latest) {
    if (!ticks_.update()) return false;
    latest = ticks_.front();
    return true;
}

ForceLoopReport ForceLoop::report() const {
    ForceLoopReport r = report_;
    r.periods = periods_.summary();
    return r;
}

void ForceLoop::run() {
    ForceLoopReport report;
    report.realtime_grant = make_this_thread_realtime(config_.realtime);
    report.realtime = report.realtime_grant.fifo;
    thread_id_.store(static_cast<int>(gettid()), std::memory_order_release);
    ForceRenderer renderer(config_.renderer);
    periods_.clear();
    jitter_.clear();
    DeviceState state;
    Vec3 last_force;
    std::int64_t previous_start = 0;
    std::int64_t work_ns = 0;  // the previous tick's body
    const ThreadCounters counters_before = read_this_thread_counters();
    std::int64_t deadline = monotonic_ns() + period_ns_;
    bool unseen_snapshot = false;
    double fade = 1.0;  // the stop ramp
    const double fade_step =
        config_.stop_ramp_ns > 0
            ? static_cast<double>(period_ns_) / static_cast<double>(config_.stop_ramp_ns)
            : 1.0;
    for (std::uint64_t tick = 0;; ++tick) {
        const bool stopping = stop_requested_.load(std::memory_order_acquire);
        if (stopping && (fade <= 0.0 || length(last_force) == 0.0)) break;
        // Sleep, then spin to the deadline, timing both.
        TickPhases phases;
        phases.tick = tick;
        phases.work_ns = work_ns;
        const auto sleep_point = deadline - config_.spin_ns;
        std::int64_t now = monotonic_ns();
        if (now < sleep_point) {
            sleep_until_ns(sleep_point, config_.absolute_sleep);
            now = monotonic_ns();
            phases.slept = true;
            phases.wake_late_ns = std::max<std::int64_t>(0, now - sleep_point);
        }
        while (now < deadline) {
            const std::int64_t t = monotonic_ns();
            phases.spin_gap_ns = std::max(phases.spin_gap_ns, t - now);
            now = t;
        }
        if (tick > 0) {
            periods_.add(now - previous_start);
            phases.start_ns = now;
            phases.period_ns = now - previous_start;
            phases.lateness_ns = now - deadline;
            phases.cpu = current_cpu();
            jitter_.add(phases);
        }
        previous_start = now;

        if (device_.read(state) == ReadStatus::Lost) {
            report.device_lost = true;
            break;
        }
        // A snapshot taken while the device has no pose yet is handed over at its first pose.
        if (snapshots_.update()) {
            ++report.snapshots_taken;
            unseen_snapshot = true;
        }
        TickOutput out;
        if (state.valid) {
            out =
                renderer.tick(state.position, now, unseen_snapshot ? &snapshots_.front() : nullptr);
            unseen_snapshot = false;
        }
        if (stopping) {
            fade = std::max(0.0, fade - fade_step);
            out.force = out.force * fade;
        }
        device_.write_force({out.force, out.contact, out.stale});

        TickRecord& record = ticks_.back();
        record = {tick, now, state, out.force, out.contact, out.stale, out.snapshot_sequence};
        if (records_.size() < records_.capacity()) records_.push_back(record);
        ticks_.publish();

        const double magnitude = length(out.force);
        report.max_force = std::max(report.max_force, magnitude);
        const double jump = length(out.force - last_force);
        report.max_force_jump = std::max(report.max_force_jump, jump);
        if (jump > 0.5) ++report.force_jumps_over_half_newton;
        if (out.stale) ++report.stale_ticks;
        last_force = out.force;
        report.ticks = tick + 1;
        work_ns = monotonic_ns() - now;

        deadline += period_ns_;
        // Ticks missed entirely are not made up: when the next deadline has already passed,
        // the schedule restarts from now.
        if (deadline <= now) deadline = now + period_ns_;
    }
    device_.write_force({});
    report.during_ticks = difference(read_this_thread_counters(), counters_before);
    report.jitter = jitter_.summary();
    report_ = report;
    running_.store(false, std::memory_order_release);
}

}  // namespace sandtin::haptics
