#include "haptics/diagnostics/loop_jitter.hpp"

#include <algorithm>
#include <stdexcept>

namespace sandtin::haptics {

const char* to_string(LateCause cause) {
    switch (cause) {
        case LateCause::Work:
            return "work";
        case LateCause::Wakeup:
            return "wakeup";
        case LateCause::SpinGap:
            return "spin_gap";
    }
    return "unknown";
}

LateCause late_cause(const TickPhases& t) {
    if (t.work_ns >= t.wake_late_ns && t.work_ns >= t.spin_gap_ns) return LateCause::Work;
    return t.wake_late_ns >= t.spin_gap_ns ? LateCause::Wakeup : LateCause::SpinGap;
}

JitterStats::JitterStats(std::int64_t late_threshold_ns, std::size_t event_capacity)
    : threshold_ns_(late_threshold_ns) {
    if (late_threshold_ns <= 0)
        throw std::invalid_argument("jitter stats: late threshold must be > 0");
    events_.reserve(event_capacity);
}

void JitterStats::clear() {
    summary_ = {};
    events_.clear();
}

void JitterStats::add(const TickPhases& t) {
    JitterSummary& s = summary_;
    ++s.ticks;
    s.max_work_ns = std::max(s.max_work_ns, t.work_ns);
    s.max_wake_late_ns = std::max(s.max_wake_late_ns, t.wake_late_ns);
    s.max_spin_gap_ns = std::max(s.max_spin_gap_ns, t.spin_gap_ns);
    if (t.slept && t.lateness_ns > 0 && t.spin_gap_ns < t.lateness_ns &&
        t.wake_late_ns >= t.lateness_ns) {
        ++s.wakes_after_deadline;
    }
    if (t.spin_gap_ns > kLongGapNs) {
        ++s.long_spin_gaps;
        s.long_spin_gap_total_ns += t.spin_gap_ns;
    }
    if (s.ticks == 1 || t.period_ns > s.worst.period_ns) s.worst = t;
    if (t.period_ns <= threshold_ns_) return;
    ++s.late_ticks;
    switch (late_cause(t)) {
        case LateCause::Work:
            ++s.late_by_work;
            break;
        case LateCause::Wakeup:
            ++s.late_by_wakeup;
            break;
        case LateCause::SpinGap:
            ++s.late_by_spin_gap;
            break;
    }
    if (events_.size() < events_.capacity()) {
        events_.push_back(t);
    } else {
        ++s.late_ticks_not_kept;
    }
}

}  // namespace sandtin::haptics
