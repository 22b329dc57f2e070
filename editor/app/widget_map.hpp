#pragma once
// Where the panels drew their named controls, frame by frame, in window pixels. Scripted runs
// click and hover controls by name through real input (x_input.hpp), and the xdotool test
// reads the map from a file (--widget-map); both look at the last frame drawn, which is what
// the screen shows when the next event arrives.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sandtin::editor {

struct WidgetRect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the part of the control that can be seen
    bool enabled = true;

    double centre_x() const { return 0.5 * (double{x0} + double{x1}); }
    double centre_y() const { return 0.5 * (double{y0} + double{y1}); }
    friend bool operator==(const WidgetRect&, const WidgetRect&) = default;
};

class WidgetMap {
  public:
    /// Starts a frame's notes.
    void begin_frame();
    /// Call right after the ImGui item `name` (inside its window). Items scrolled out of
    /// sight or clipped away are not noted (a pointer cannot reach them).
    void note(const std::string& name);
    /// A state of the editor rather than a control, noted with an empty rectangle: "job" while
    /// long work runs, so the xdotool test can wait for it to end as a hand waits for the bar.
    void note_state(const std::string& name) { drawing_[name] = WidgetRect{}; }
    /// Ends a frame (call after ImGui::Render): what it noted becomes the map to look things up
    /// in, and where ImGui's windows are is noted (the panels, the Stats window, an open
    /// combo's list), but not tooltips, which take no clicks, nor modal prompts, whose owner
    /// knows better whether they are still open.
    void end_frame();
    /// Whether the point (window pixels) lies on a window the last frame drew. Unlike
    /// ImGui's WantCaptureMouse this can be asked of events that arrive before the next frame,
    /// where the pointer is then, not where it was.
    bool covers(double x, double y) const;
    /// Call when the tooltip `text` is shown this frame.
    void note_tooltip(const std::string& text) { tooltip_ = text; }

    /// The control `name` as the last frame drew it.
    std::optional<WidgetRect> find(const std::string& name) const;
    /// Whether `name` was drawn at the same place in the last two frames (a window that just
    /// appeared is still sizing itself in its first frame).
    bool settled(const std::string& name) const;
    /// The last tooltip shown (empty before any).
    const std::string& last_tooltip() const { return tooltip_; }

    /// {"name": [x0, y0, x1, y1, enabled], ...} of the last complete frame.
    nlohmann::json to_json() const;

  private:
    std::map<std::string, WidgetRect> drawing_, last_, before_last_;
    std::vector<WidgetRect> windows_;
    std::string tooltip_;
};

}  // namespace sandtin::editor
