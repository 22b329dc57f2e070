#pragma once
// When the interactive loop draws and whether it blocks: plain decisions, unit-tested without
// a window. Idle means blocking event waits (no frame, no GPU submission); a minimised window
// (0 x 0 framebuffer) never draws and never spins, even while erosion would run: the physics
// resumes with the next frame after the window is restored.
//
// With a haptic device connected, the waits are timed so the Haptics panel's live rate and force
// are redrawn every kHapticReadoutSeconds; the force loop's snapshot is kept current meanwhile
// by the session's heartbeat thread (haptics/snapshot_heartbeat.hpp), not by frames.
//
// While long work runs on a worker (an import, an open, an export: background_job.hpp) the
// window redraws its progress bar every kJobRefreshSeconds: frames keep coming, well within
// 100 ms, without spinning on the CPU the worker needs.

namespace sandtin::editor {

struct LoopState {
    int framebuffer_width = 0;  ///< pixels; 0 while minimised
    int framebuffer_height = 0;
    bool redraw_pending = false;     ///< frames still owed after an event (ImGui settles)
    bool dragging = false;           ///< a tool is being applied
    bool prompt_open = false;        ///< a modal waits for an answer
    bool eroding = false;            ///< erosion runs and the sand is not at rest
    bool water_moving = false;       ///< water flows (or a source adds some) and is not at rest
    bool haptics_connected = false;  ///< a force loop reads the snapshots we publish
    bool job_running = false;        ///< long work on a worker: its progress bar is redrawn
};

/// Seconds between frames drawn while idle with a haptic device (the panel's live readout).
inline constexpr double kHapticReadoutSeconds = 0.5;
/// Seconds between frames drawn while a job runs on a worker (its bar, elapsed and estimate):
/// frames go on, but do not spin, so the worker has the CPU it needs.
inline constexpr double kJobRefreshSeconds = 0.05;
/// How long wait_for_events may block: 0 polls, a negative value waits for the next event.
inline constexpr double kWaitForEvent = -1.0;

/// A framebuffer with no pixels cannot be drawn to (and a swapchain cannot be made for it).
constexpr bool can_draw(int framebuffer_width, int framebuffer_height) {
    return framebuffer_width > 0 && framebuffer_height > 0;
}

/// Poll for events and draw continuously (true), or block until the next event (false).
constexpr bool wants_continuous_frames(const LoopState& s) {
    if (!can_draw(s.framebuffer_width, s.framebuffer_height)) return false;
    return s.redraw_pending || s.dragging || s.prompt_open || s.eroding || s.water_moving;
}

/// How long the loop may wait for events (seconds): 0 = poll and go on, kWaitForEvent = block
/// until one arrives, otherwise a timeout (the haptic readout).
constexpr double event_wait_seconds(const LoopState& s) {
    if (wants_continuous_frames(s)) return 0.0;
    const bool visible = can_draw(s.framebuffer_width, s.framebuffer_height);
    if (visible && s.job_running) return kJobRefreshSeconds;
    return visible && s.haptics_connected ? kHapticReadoutSeconds : kWaitForEvent;
}

/// Whether to draw once the wait is over. `s` is the state the wait was chosen from;
/// `event_arrived` says whether an input or window event came in during it;
/// `seconds_since_frame` is the time since the last frame was drawn.
constexpr bool draw_after_wait(const LoopState& s, bool event_arrived, double seconds_since_frame) {
    if (!can_draw(s.framebuffer_width, s.framebuffer_height)) return false;
    if (wants_continuous_frames(s) || event_arrived) return true;
    // A timed wait may end a hair early: half the period is the job's refresh.
    if (s.job_running && seconds_since_frame >= 0.5 * kJobRefreshSeconds) return true;
    return s.haptics_connected && seconds_since_frame >= kHapticReadoutSeconds;
}

}  // namespace sandtin::editor
