#include "haptics/force_loop.hpp"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sandtin::haptics {

std::int64_t monotonic_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::int64_t loop_period_ns(const ForceLoopConfig& c) {
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

namespace {

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

ForceLoop::ForceLoop(HapticDevice& device, ForceLoopConfig config, LoopObserver* observer)
    : device_(device),
      config_(with_rate(config)),
      observer_(observer),
      period_ns_(loop_period_ns(config_)),
      periods_(period_ns_) {
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
    stop_requested_.store(false);
    running_.store(true, std::memory_order_release);
    thread_ = std::thread([this] { run(); });
}

void ForceLoop::stop() {
    stop_requested_.store(true, std::memory_order_release);
    if (thread_.joinable()) thread_.join();
    running_.store(false, std::memory_order_release);
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

// What the ticks share, owned by whichever thread holds the tick token.
struct ForceLoop::TickState {
    explicit TickState(const ForceRendererConfig& c) : renderer(c) {}
    ForceRenderer renderer;
    DeviceState state;
    Vec3 last_force;
    std::int64_t previous_start = 0;
    std::int64_t work_ns = 0;  // the previous tick's body
    bool unseen_snapshot = false;
    double fade = 1.0;  // the stop ramp
    ForceLoopReport report;
};

void ForceLoop::run() {
    TickState s(config_.renderer);
    s.report.realtime_grant = make_this_thread_realtime(config_.realtime);
    s.report.realtime = s.report.realtime_grant.fifo;
    thread_id_.store(static_cast<int>(gettid()), std::memory_order_release);
    periods_.clear();
    if (observer_ != nullptr) observer_->thread_started();
    deadline_.store(monotonic_ns() + period_ns_, std::memory_order_relaxed);
    token_.reset();
    std::thread backup;
    if (config_.backup_thread) {
        backup = std::thread([this, &s] {
            RealtimeRequest r = config_.realtime;
            r.lock_memory = false;  // process-wide: done once, by the primary
            r.cpu = config_.backup_cpu;
            make_this_thread_realtime(r);
            wait_and_tick(s, true);
        });
    }
    // After starting the backup: creating a thread faults in the primary, before any tick.
    if (observer_ != nullptr) observer_->ticks_starting();
    wait_and_tick(s, false);
    if (backup.joinable()) backup.join();
    if (observer_ != nullptr) observer_->ticks_ended();
    report_ = s.report;
    running_.store(false, std::memory_order_release);
}

void ForceLoop::wait_and_tick(TickState& s, bool backup) {
    for (;;) {
        const TickToken::Seen seen = token_.load();
        if (seen.finished()) return;
        if (seen.owned()) continue;  // the other thread is ticking: a few us
        const std::int64_t deadline = deadline_.load(std::memory_order_acquire);
        if (token_.load().word != seen.word) continue;  // changed meanwhile
        const std::uint64_t tick = seen.tick();
        // Sleep, then spin to the deadline, timing both. The backup wakes only `backup_margin_ns`
        // after the deadline, to take the tick if the primary has not (its wake-up was late).
        TickPhases phases;
        phases.tick = tick;
        const auto wake_point =
            backup ? deadline + config_.backup_margin_ns : deadline - config_.spin_ns;
        std::int64_t now = monotonic_ns();
        if (now < wake_point) {
            sleep_until_ns(wake_point, config_.absolute_sleep);
            now = monotonic_ns();
            phases.slept = true;
            phases.wake_late_ns = std::max<std::int64_t>(0, now - wake_point);
        }
        while (now < deadline) {
            const std::int64_t t = monotonic_ns();
            phases.spin_gap_ns = std::max(phases.spin_gap_ns, t - now);
            now = t;
        }
        // Fails when the other thread took this tick or ended the loop while we waited.
        if (!token_.try_claim(seen)) continue;
        phases.work_ns = s.work_ns;
        const bool more = run_tick(s, tick, now, deadline, phases, backup);
        token_.release(tick, !more);
        if (!more) return;
    }
}

bool ForceLoop::run_tick(TickState& s, std::uint64_t tick, std::int64_t now, std::int64_t deadline,
                         TickPhases phases, bool backup) {
    const bool stopping = stop_requested_.load(std::memory_order_acquire);
    if (stopping && (s.fade <= 0.0 || length(s.last_force) == 0.0)) {
        device_.write_force({});
        return false;
    }
    if (tick > 0) {
        periods_.add(now - s.previous_start);
        if (observer_ != nullptr) {
            phases.start_ns = now;
            phases.period_ns = now - s.previous_start;
            phases.lateness_ns = now - deadline;
            phases.cpu = current_cpu();
            observer_->ticked(phases);
        }
    }
    s.previous_start = now;
    if (backup) ++s.report.ticks_by_backup;

    if (device_.read(s.state) == ReadStatus::Lost) {
        s.report.device_lost = true;
        device_.write_force({});
        return false;
    }
    // A snapshot taken while the device has no pose yet is handed over at its first pose.
    if (snapshots_.update()) {
        ++s.report.snapshots_taken;
        s.unseen_snapshot = true;
    }
    TickOutput out;
    if (s.state.valid) {
        out = s.renderer.tick(s.state.position, now,
                              s.unseen_snapshot ? &snapshots_.front() : nullptr);
        s.unseen_snapshot = false;
    }
    if (stopping) {
        const double fade_step =
            config_.stop_ramp_ns > 0
                ? static_cast<double>(period_ns_) / static_cast<double>(config_.stop_ramp_ns)
                : 1.0;
        s.fade = std::max(0.0, s.fade - fade_step);
        out.force = out.force * s.fade;
    }
    device_.write_force({out.force, out.contact, out.stale});

    TickRecord& record = ticks_.back();
    record = {tick, now, s.state, out.force, out.contact, out.stale, out.snapshot_sequence};
    if (records_.size() < records_.capacity()) records_.push_back(record);
    ticks_.publish();

    ForceLoopReport& report = s.report;
    const double magnitude = length(out.force);
    report.max_force = std::max(report.max_force, magnitude);
    const double jump = length(out.force - s.last_force);
    report.max_force_jump = std::max(report.max_force_jump, jump);
    if (jump > 0.5) ++report.force_jumps_over_half_newton;
    if (out.stale) ++report.stale_ticks;
    s.last_force = out.force;
    report.ticks = tick + 1;
    s.work_ns = monotonic_ns() - now;

    // Ticks missed entirely are not made up: when the next deadline has already passed, the
    // schedule restarts from now.
    std::int64_t next = deadline + period_ns_;
    if (next <= now) next = now + period_ns_;
    deadline_.store(next, std::memory_order_release);
    return true;
}

}  // namespace sandtin::haptics
