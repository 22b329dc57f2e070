#pragma once
// The controls the panels are built from, beyond ImGui's own: sliders over a setting's range
// (clamped when a value is typed in), and a path field with its button.

#include <imgui.h>

#include <cstddef>
#include <string>

#include "editor_settings.hpp"
#include "widget_map.hpp"

namespace sandtin::editor {

/// The label the panels' label column is sized for: the longest one beside a control.
inline constexpr const char* kWidestLabel = "Settle margin (%)";

/// A slider over `range` at the terrain size `size` (metres, or m³), shown in the unit that
/// suits its largest value: "name (unit per)". The ImGui id is the name alone, so a change of
/// unit is not a new widget. A value typed in (Ctrl+click) is clamped to the range, as a drag
/// is: a tool never receives a size, depth or volume it would refuse.
bool range_slider(const char* name, const char* per, double& value, const SettingRange& range,
                  double size, const char* format);

/// A plain slider over `range` (no unit scaling), shown times `shown_per_unit` (100: percent),
/// clamped as range_slider is.
bool plain_slider(const char* label, double& value, const SettingRange& range, const char* format,
                  double shown_per_unit = 1.0, ImGuiSliderFlags flags = ImGuiSliderFlags_None);

/// A material's name as the panels show it: "dry_sand" reads "dry sand".
std::string shown_name(std::string name);

/// A path field filling its row with its button at the right end, "[path ......][Button]";
/// `hint` shows while the field is empty, and hovering the field shows its whole path. The
/// field is noted in `widgets` as `field_name`. True when the button was pressed; the caller's
/// `ui` that follows names and explains the button.
bool path_field(WidgetMap& widgets, const char* field_name, const char* hint, char* buffer,
                std::size_t size, const char* button);

}  // namespace sandtin::editor
