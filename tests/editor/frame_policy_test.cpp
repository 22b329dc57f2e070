// The interactive loop's decisions (frame_policy.hpp): a minimised window never draws and
// never spins, whatever else is going on; a visible one draws continuously exactly while
// something is happening, and blocks on events otherwise.

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

}  // namespace
}  // namespace sandtin::editor
