#include "widget_map.hpp"

#include <imgui.h>
#include <imgui_internal.h>

namespace sandtin::editor {

void WidgetMap::begin_frame() {
    drawing_.clear();
}

void WidgetMap::note(const std::string& name) {
    const ImGuiWindow* window = ImGui::GetCurrentWindow();
    ImRect item(ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
    // What a pointer can reach: inside the window's visible region and the display.
    ImRect seen = window->InnerClipRect;
    seen.ClipWith(ImRect(ImVec2(0.0f, 0.0f), ImGui::GetIO().DisplaySize));
    item.ClipWith(seen);
    if (item.GetWidth() <= 0.0f || item.GetHeight() <= 0.0f) return;
    const bool enabled = (GImGui->LastItemData.InFlags & ImGuiItemFlags_Disabled) == 0;
    drawing_[name] = WidgetRect{item.Min.x, item.Min.y, item.Max.x, item.Max.y, enabled};
}

void WidgetMap::end_frame() {
    before_last_ = std::move(last_);
    last_ = std::move(drawing_);
    drawing_.clear();
    windows_.clear();
    for (const ImGuiWindow* w : GImGui->Windows) {
        if (!w->Active || w->Hidden) continue;
        if ((w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_Modal)) != 0) continue;
        windows_.push_back({w->Pos.x, w->Pos.y, w->Pos.x + w->Size.x, w->Pos.y + w->Size.y, true});
    }
}

bool WidgetMap::covers(double x, double y) const {
    for (const WidgetRect& r : windows_) {
        if (x >= double{r.x0} && x < double{r.x1} && y >= double{r.y0} && y < double{r.y1})
            return true;
    }
    return false;
}

std::optional<WidgetRect> WidgetMap::find(const std::string& name) const {
    const auto it = last_.find(name);
    if (it == last_.end()) return std::nullopt;
    return it->second;
}

bool WidgetMap::settled(const std::string& name) const {
    const auto a = last_.find(name), b = before_last_.find(name);
    return a != last_.end() && b != before_last_.end() && a->second == b->second;
}

nlohmann::json WidgetMap::to_json() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, r] : last_)
        j[name] = {r.x0, r.y0, r.x1, r.y1, r.enabled};
    return j;
}

}  // namespace sandtin::editor
