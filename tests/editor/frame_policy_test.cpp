// The interactive loop's decisions (frame_policy.hpp): a minimised window never draws and
// never spins, whatever else is going on; a visible one draws continuously exactly while
// something is happening, and blocks on events otherwise. With a haptic device connected an
// idle window wakes now and then to redraw the live readout, and only for that.

#include <gtest/gtest.h>

#include "frame_policy.hpp"

namespace sandtin::editor {
namespace {

TEST(FramePolicy, MinimisedWindowNeitherDrawsNorSpins) {
    EXPECT_FALSE(can_draw(0, 0));
    EXPECT_FALSE(can_draw(0, 720));
    EXPECT_FALSE(can_draw(1280, 0));
    EXPECT_TRUE(can_draw(1, 1));
    // Every combination of reasons to draw: none makes a 0 x 0 window poll.
    for (int bits = 0; bits < 16; ++bits) {
        LoopState s;
        s.redraw_pending = (bits & 1) != 0;
        s.dragging = (bits & 2) != 0;
        s.prompt_open = (bits & 4) != 0;
        s.eroding = (bits & 8) != 0;
        EXPECT_FALSE(wants_continuous_frames(s)) << bits;
        s.framebuffer_width = 1280;
        s.framebuffer_height = 720;
        EXPECT_EQ(wants_continuous_frames(s), bits != 0) << bits;
    }
}

LoopState visible() {
    LoopState s;
    s.framebuffer_width = 1280;
    s.framebuffer_height = 720;
    return s;
}

TEST(FramePolicy, IdleWithoutHapticsBlocksAndDrawsOnlyForEvents) {
    const LoopState s = visible();
    EXPECT_EQ(event_wait_seconds(s), kWaitForEvent);
    EXPECT_TRUE(draw_after_wait(s, true, 0.0));
    // Woken without an event (a bounded wait that timed out): no frame, however long ago the
    // last one was.
    EXPECT_FALSE(draw_after_wait(s, false, 3600.0));
    LoopState eroding = s;
    eroding.eroding = true;
    EXPECT_EQ(event_wait_seconds(eroding), 0.0);
    EXPECT_TRUE(draw_after_wait(eroding, false, 0.0));
}

TEST(FramePolicy, IdleWithHapticsRedrawsOnlyTheReadoutNowAndThen) {
    LoopState s = visible();
    s.haptics_connected = true;
    EXPECT_EQ(event_wait_seconds(s), kHapticReadoutSeconds);
    EXPECT_FALSE(draw_after_wait(s, false, 0.0));
    EXPECT_FALSE(draw_after_wait(s, false, 0.9 * kHapticReadoutSeconds));
    EXPECT_TRUE(draw_after_wait(s, false, kHapticReadoutSeconds));
    EXPECT_TRUE(draw_after_wait(s, true, 0.0));  // any event still draws at once
    s.dragging = true;
    EXPECT_EQ(event_wait_seconds(s), 0.0);
    EXPECT_TRUE(draw_after_wait(s, false, 0.0));
}

TEST(FramePolicy, MinimisedWithHapticsStillBlocksAndNeverDraws) {
    LoopState s;
    s.haptics_connected = true;
    s.redraw_pending = true;
    s.eroding = true;
    EXPECT_EQ(event_wait_seconds(s), kWaitForEvent);
    EXPECT_FALSE(draw_after_wait(s, true, 3600.0));
    EXPECT_FALSE(draw_after_wait(s, false, 3600.0));
}

TEST(FramePolicy, AJobRedrawsItsBarWithoutSpinning) {
    LoopState s = visible();
    s.job_running = true;
    // Frames go on (the bar, elapsed, the estimate) at the job's refresh, not back to back:
    // the worker has the CPU.
    EXPECT_FALSE(wants_continuous_frames(s));
    EXPECT_EQ(event_wait_seconds(s), kJobRefreshSeconds);
    EXPECT_LE(kJobRefreshSeconds, 0.1) << "the frame must not stall for more than 100 ms";
    EXPECT_TRUE(draw_after_wait(s, false, kJobRefreshSeconds));
    EXPECT_FALSE(draw_after_wait(s, false, 0.0));
    // With a haptic device too, the job's shorter period wins.
    s.haptics_connected = true;
    EXPECT_EQ(event_wait_seconds(s), kJobRefreshSeconds);
    // Minimised: nothing, job or not.
    s.framebuffer_width = 0;
    EXPECT_EQ(event_wait_seconds(s), kWaitForEvent);
    EXPECT_FALSE(draw_after_wait(s, true, 1.0));
}

}  // namespace
}  // namespace sandtin::editor
