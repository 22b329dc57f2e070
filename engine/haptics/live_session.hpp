#pragma once
// The simulation side of a live haptic session, and its recording.
//
// Threaded (the editor, `sandtin bench haptics`, the UDP session): the force loop runs on its
// own thread; each LiveSession::step() on the simulation thread takes the newest device tick
// the loop published, applies it (LiveEditor), remembers it as an edit, and publishes a fresh
// snapshot. Which ticks the simulation sees depends on timing, so the recording keeps the
// ones it used: replaying them gives the same terrain whatever the timing was.
//
// Lock-step (tests, offline checks): run_lockstep drives the same editor and the same
// ForceRenderer tick by tick on a synthetic clock, with a simulation step every N ticks:
// deterministic, and no thread.

#include <cstdint>
#include <vector>

#include "haptics/force_loop.hpp"
#include "haptics/force_renderer.hpp"
#include "haptics/haptic_recording.hpp"
#include "haptics/live_editor.hpp"
#include "haptics/trajectory.hpp"

namespace sandtin::haptics {

struct SessionStepReport {
    bool consumed = false;  ///< a new device tick was applied
    EditResult edit;
    double ms = 0.0;  ///< wall time of the step
};

class LiveSession {
  public:
    /// The editor and loop must outlive the session.
    LiveSession(LiveEditor& editor, ForceLoop& loop);

    /// One simulation step (see the header comment). Without a new valid device tick it does
    /// nothing and returns consumed = false.
    SessionStepReport step();

    const std::vector<EditInput>& edits() const { return edits_; }
    std::uint64_t steps() const { return steps_; }

  private:
    LiveEditor& editor_;
    ForceLoop& loop_;
    std::vector<EditInput> edits_;
    std::uint64_t last_tick_ = 0;
    bool has_tick_ = false;
    std::uint64_t steps_ = 0;
};

/// The recording of a finished session: `ticks` from the loop's record (ForceLoop::records()
/// or LockstepResult::ticks), the edits the simulation used, and the header fields.
HapticRecording make_recording(double rate_hz, const nlohmann::json& tool_json,
                               const LiveEditSettings& edit,
                               const std::optional<ScriptTerrain>& terrain,
                               Generation start_generation, const TerrainSummary& start,
                               const std::vector<TickRecord>& ticks,
                               const std::vector<EditInput>& edits, const Tin& result);

struct LockstepResult {
    std::vector<TickRecord> ticks;
    std::vector<EditInput> edits;
    double max_force_jump = 0.0;  ///< N between consecutive ticks
    double max_force = 0.0;       ///< N
    std::size_t stamps = 0;
};

/// Plays `trajectory` through `editor` and a ForceRenderer: at tick t the device is at
/// sample t; every `sim_every` ticks (from tick 0) the editor applies that sample and a
/// snapshot is published; the renderer ticks with time t / rate.
LockstepResult run_lockstep(LiveEditor& editor, const Trajectory& trajectory,
                            const ForceRendererConfig& renderer, std::uint32_t sim_every);

}  // namespace sandtin::haptics
