#include "panel_widgets.hpp"

#include <algorithm>

#include "terrain_scale.hpp"

namespace sandtin::editor {

bool range_slider(const char* name, const char* per, double& value, const SettingRange& range,
                  double size, const char* format) {
    const DisplayUnit unit = range.scaling == Scaling::Volume ? volume_unit(range.hi_at(size))
                                                              : length_unit(range.hi_at(size));
    const std::string label =
        std::string(name) + " (" + unit.suffix + per + ")###" + std::string(name);
    auto shown = [&](double v) { return static_cast<float>(v / unit.metres); };
    float v = shown(value);
    if (!ImGui::SliderFloat(label.c_str(), &v, shown(range.lo_at(size)), shown(range.hi_at(size)),
                            format, ImGuiSliderFlags_AlwaysClamp))
        return false;
    value = range.clamp(static_cast<double>(v) * unit.metres, size);
    return true;
}

bool plain_slider(const char* label, double& value, const SettingRange& range, const char* format,
                  double shown_per_unit, ImGuiSliderFlags flags) {
    float v = static_cast<float>(value * shown_per_unit);
    if (!ImGui::SliderFloat(label, &v, static_cast<float>(range.lo * shown_per_unit),
                            static_cast<float>(range.hi * shown_per_unit), format,
                            flags | ImGuiSliderFlags_AlwaysClamp))
        return false;
    value = range.clamp(static_cast<double>(v) / shown_per_unit, 1.0);
    return true;
}

std::string shown_name(std::string name) {
    std::replace(name.begin(), name.end(), '_', ' ');
    return name;
}

bool path_field(WidgetMap& widgets, const char* field_name, const char* hint, char* buffer,
                std::size_t size, const char* button) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float button_width = ImGui::CalcTextSize(button).x + 2.0f * style.FramePadding.x;
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - button_width - style.ItemSpacing.x);
    ImGui::InputTextWithHint((std::string("##") + field_name).c_str(), hint, buffer, size);
    widgets.note(field_name);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", buffer[0] != '\0' ? buffer : hint);
    ImGui::SameLine();
    return ImGui::Button(button);
}

}  // namespace sandtin::editor
