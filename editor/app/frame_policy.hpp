#pragma once
// When the interactive loop draws and whether it blocks: plain decisions, unit-tested without
// a window. Idle means blocking event waits (no frame, no GPU submission); a minimised window
// (0 x 0 framebuffer) never draws and never spins, even while erosion would run: the physics
// resumes with the next frame after the window is restored.

namespace sandtin::editor {

struct LoopState {
    int framebuffer_width = 0;  ///< pixels; 0 while minimised
    int framebuffer_height = 0;
    bool redraw_pending = false;  ///< frames still owed after an event (ImGui settles)
    bool dragging = false;        ///< a tool is being applied
    bool prompt_open = false;     ///< a modal waits for an answer
    bool eroding = false;         ///< erosion runs and the sand is not at rest
};

/// A framebuffer with no pixels cannot be drawn to (and a swapchain cannot be made for it).
constexpr bool can_draw(int framebuffer_width, int framebuffer_height) {
    return framebuffer_width > 0 && framebuffer_height > 0;
}

/// Poll for events and draw continuously (true), or block until the next event (false).
constexpr bool wants_continuous_frames(const LoopState& s) {
    if (!can_draw(s.framebuffer_width, s.framebuffer_height)) return false;
    return s.redraw_pending || s.dragging || s.prompt_open || s.eroding;
}

}  // namespace sandtin::editor
