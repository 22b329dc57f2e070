#include "haptics/live_session.hpp"
#include "util/elapsed_ms.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sandtin::haptics {

LiveSession::LiveSession(LiveEditor& editor, ForceLoop& loop) : editor_(editor), loop_(loop) {}

SessionStepReport LiveSession::step() {
    SessionStepReport report;
    TickRecord latest;
    if (!loop_.poll(latest) || !latest.device.valid) return report;
    if (has_tick_ && latest.tick == last_tick_) return report;
    const auto t0 = std::chrono::steady_clock::now();
    has_tick_ = true;
    last_tick_ = latest.tick;
    const EditInput input{latest.tick, latest.device.position, latest.device.buttons};
    report.edit = editor_.apply(input);
    edits_.push_back(input);
    loop_.publish(editor_.snapshot());
    report.consumed = true;
    ++steps_;
    report.ms = elapsed_ms(t0);
    return report;
}

HapticRecording make_recording(double rate_hz, const nlohmann::json& tool_json,
                               const LiveEditSettings& edit,
                               const std::optional<ScriptTerrain>& terrain,
                               Generation start_generation, const TerrainSummary& start,
                               const std::vector<TickRecord>& ticks,
                               const std::vector<EditInput>& edits, const Tin& result) {
    HapticRecording r;
    r.rate_hz = rate_hz;
    r.tool = tool_json;
    r.edit = edit;
    r.terrain = terrain;
    r.next_generation = start_generation;
    r.start = start;
    r.ticks.reserve(ticks.size());
    for (const TickRecord& t : ticks) {
        if (!t.device.valid) continue;
        r.ticks.push_back({t.device.position, t.device.buttons, t.force});
    }
    r.edits = edits;
    r.result = summarise(result);
    return r;
}

LockstepResult run_lockstep(LiveEditor& editor, const Trajectory& trajectory,
                            const ForceRendererConfig& config, std::uint32_t sim_every) {
    if (sim_every < 1) throw std::invalid_argument("lockstep: sim_every must be >= 1");
    ForceRendererConfig c = config;
    c.rate_hz = trajectory.rate_hz;
    ForceRenderer renderer(c);
    const double period_ns = 1e9 / trajectory.rate_hz;
    LockstepResult out;
    out.ticks.reserve(trajectory.samples.size());
    HapticSnapshot snapshot;
    std::uint64_t sequence = 0;
    Vec3 last_force;
    for (std::size_t t = 0; t < trajectory.samples.size(); ++t) {
        const TrajectorySample& s = trajectory.samples[t];
        const auto now =
            static_cast<std::int64_t>(std::llround(static_cast<double>(t) * period_ns));
        const bool sim = t % sim_every == 0;
        if (sim) {
            const EditInput input{t, s.position, s.buttons};
            out.stamps += editor.apply(input).stamps;
            out.edits.push_back(input);
            snapshot = editor.snapshot();
            snapshot.sequence = ++sequence;
            snapshot.published_ns = now;
        }
        const TickOutput o = renderer.tick(s.position, now, sim ? &snapshot : nullptr);
        TickRecord r;
        r.tick = t;
        r.time_ns = now;
        r.device = {s.position, s.buttons, static_cast<std::uint32_t>(t), true};
        r.force = o.force;
        r.contact = o.contact;
        r.stale = o.stale;
        r.snapshot_sequence = o.snapshot_sequence;
        out.ticks.push_back(r);
        out.max_force = std::max(out.max_force, length(o.force));
        out.max_force_jump = std::max(out.max_force_jump, length(o.force - last_force));
        last_force = o.force;
    }
    return out;
}

}  // namespace sandtin::haptics
