#include "layout_probe.hpp"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>

namespace sandtin::editor {

// ImGui keeps, per window, the right end of the widest control drawn so far in the frame
// (DC.CursorMaxPos.x, the width the window would need). The probe restarts it at the section's
// left edge, reads it at the end of the section, and gives the window back the larger of the
// two, so the window's own sizing is unchanged.

void LayoutProbe::begin(const std::string& section) {
    // A section left open (a panel that threw) is simply replaced: measuring must never stop
    // the editor.
    ImGuiWindow* window = ImGui::GetCurrentWindow();
    section_ = section;
    window_reach_ = window->DC.CursorMaxPos.x;
    window->DC.CursorMaxPos.x = window->DC.CursorPos.x;
}

void LayoutProbe::end() {
    if (section_.empty()) return;
    ImGuiWindow* window = ImGui::GetCurrentWindow();
    const float reach = window->DC.CursorMaxPos.x;
    // A window hidden while it sizes itself (an auto-resizing one's first frame) shows
    // nothing that could be cut off: only what is drawn on screen counts.
    const float overflow = window->Hidden ? 0.0f : std::max(0.0f, reach - window->WorkRect.Max.x);
    float& widest = overflow_px_[section_];
    widest = std::max(widest, overflow);
    window->DC.CursorMaxPos.x = std::max(window_reach_, reach);
    section_.clear();
}

void LayoutProbe::item_visible(const std::string& name) {
    const ImGuiWindow* window = ImGui::GetCurrentWindow();
    if (window->Hidden) return;  // sizing itself: nothing of it is on screen yet (end())
    const ImRect item(ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
    // What can be seen: the window's inner region (inside its scrollbars, and inside the
    // window, which the display may cut) within the display.
    ImRect seen = window->InnerClipRect;
    seen.ClipWith(ImRect(ImVec2(0.0f, 0.0f), ImGui::GetIO().DisplaySize));
    ImRect shown = item;
    shown.ClipWith(seen);
    const float hidden = std::max(item.GetWidth() - std::max(0.0f, shown.GetWidth()),
                                  item.GetHeight() - std::max(0.0f, shown.GetHeight()));
    float& worst = hidden_px_[name];
    worst = std::max(worst, hidden);
}

}  // namespace sandtin::editor
