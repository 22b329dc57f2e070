#pragma once
// How far a panel's controls reach past the right edge of their window, in pixels.
// The editor's panels have a fixed width, so a label or button that does not fit is cut off
// without any sign; the probe measures it each frame, and a scripted run reports it in its
// stats so that a test can see it (tests/editor/editor_xvfb_test.cpp).

#include <map>
#include <string>

namespace sandtin::editor {

class LayoutProbe {
  public:
    /// Call inside an ImGui window, right before the controls of `section` are drawn.
    void begin(const std::string& section);
    /// Call right after them (inside the same window).
    void end();
    /// The widest overflow each measured section has had, in pixels: 0 when everything fitted
    /// in every frame.
    const std::map<std::string, float>& overflow_px() const { return overflow_px_; }

    /// Call right after the item `name` (inside its window): measures how much of it lies
    /// outside what can be seen, i.e. outside its window's visible region (scrolled away or
    /// clipped) or outside the display.
    void item_visible(const std::string& name);
    /// The most pixels of each measured item's height or width ever hidden: 0 when it was
    /// wholly on screen in every frame it was drawn.
    const std::map<std::string, float>& hidden_px() const { return hidden_px_; }

  private:
    std::map<std::string, float> overflow_px_;
    std::map<std::string, float> hidden_px_;
    std::string section_;
    float window_reach_ = 0.0f;  ///< the window's widest control before the section began
};

}  // namespace sandtin::editor
