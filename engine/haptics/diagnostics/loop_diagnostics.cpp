#include "haptics/diagnostics/loop_diagnostics.hpp"

namespace sandtin::haptics {

LoopDiagnostics::LoopDiagnostics(const ForceLoopConfig& config, std::size_t late_tick_capacity)
    : jitter_(loop_period_ns(config) * 3 / 2, late_tick_capacity) {}

void LoopDiagnostics::thread_started() {
    jitter_.clear();
}

void LoopDiagnostics::ticks_starting() {
    before_ = read_this_thread_counters();
}

void LoopDiagnostics::ticked(const TickPhases& phases) {
    jitter_.add(phases);
}

void LoopDiagnostics::ticks_ended() {
    during_ticks_ = difference(read_this_thread_counters(), before_);
}

}  // namespace sandtin::haptics
