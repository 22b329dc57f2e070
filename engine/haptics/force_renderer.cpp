#include "haptics/force_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sandtin::haptics {

ForceRenderer::ForceRenderer(const ForceRendererConfig& config) : config_(config) {
    if (!(config_.rate_hz > 0.0) || !std::isfinite(config_.rate_hz))
        throw std::invalid_argument("force renderer: rate_hz must be positive");
    if (config_.ramp_ns <= 0) throw std::invalid_argument("force renderer: ramp_ns must be > 0");
    if (config_.stale_after_ns < 0)
        throw std::invalid_argument("force renderer: stale_after_ns must be >= 0");
    if (config_.min_blend_ticks < 1 || config_.max_blend_ticks < config_.min_blend_ticks)
        throw std::invalid_argument("force renderer: need 1 <= min_blend_ticks <= max_blend_ticks");
    if (!(config_.model.max_force >= 0.0) || !(config_.model.gel_force >= 0.0) ||
        !(config_.model.contact_offset >= 0.0) || !(config_.model.gel_damping >= 0.0))
        throw std::invalid_argument("force renderer: model parameters must be non-negative");
    const double period_ns = 1e9 / config_.rate_hz;
    gain_step_ = std::min(1.0, period_ns / static_cast<double>(config_.ramp_ns));
}

TickOutput ForceRenderer::tick(const Vec3& position, std::int64_t now_ns,
                               const HapticSnapshot* fresh) {
    const Vec3 velocity =
        has_previous_ ? (position - previous_position_) * config_.rate_hz : Vec3{};
    const auto remaining = [&](std::uint64_t since) {
        const double r = 1.0 - static_cast<double>(since) / static_cast<double>(blend_ticks_);
        return std::max(0.0, r);
    };

    if (fresh != nullptr && fresh->sequence != 0 &&
        (!has_snapshot_ || fresh->sequence != current_.snapshot.sequence)) {
        // What the old regime would output now (zero before the first snapshot).
        Vec3 old_out;
        if (has_snapshot_) {
            const ForceSample old_model =
                evaluate_force(current_, position, velocity, config_.model);
            if (old_model.contact)
                old_out = old_model.force + blend_offset_ * remaining(tick_ - last_arrival_tick_);
        }
        const std::uint64_t interval =
            has_snapshot_ ? tick_ - last_arrival_tick_ : config_.first_blend_ticks;
        blend_ticks_ = static_cast<std::uint32_t>(
            std::clamp<std::uint64_t>(interval, config_.min_blend_ticks, config_.max_blend_ticks));
        current_ = prepare_snapshot(*fresh);
        has_snapshot_ = true;
        last_arrival_tick_ = tick_;
        const ForceSample now_model = evaluate_force(current_, position, velocity, config_.model);
        // Out of contact under the new snapshot the output is zero anyway (the seeds' rule);
        // no offset is kept that could add force when the pen re-enters the sand.
        blend_offset_ = now_model.contact ? old_out - now_model.force : Vec3{};
    }

    TickOutput out;
    out.snapshot_sequence = has_snapshot_ ? current_.snapshot.sequence : 0;
    Vec3 force;
    if (has_snapshot_) {
        const ForceSample model = evaluate_force(current_, position, velocity, config_.model);
        out.contact = model.contact;
        if (model.contact) {
            force = model.force + blend_offset_ * remaining(tick_ - last_arrival_tick_);
            force = clamp_magnitude(force, config_.model.max_force);
        }
    }
    out.stale = !has_snapshot_ || now_ns - current_.snapshot.published_ns > config_.stale_after_ns;
    const double target_gain = out.stale ? 0.0 : 1.0;
    gain_ = target_gain > gain_ ? std::min(target_gain, gain_ + gain_step_)
                                : std::max(target_gain, gain_ - gain_step_);
    out.gain = gain_;
    out.force = force * gain_;

    previous_position_ = position;
    has_previous_ = true;
    ++tick_;
    return out;
}

}  // namespace sandtin::haptics
