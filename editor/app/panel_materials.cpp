// The Materials panel: the scene's material table.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::panel_materials() {
    std::vector<Material> all = doc_.materials().all();
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Material& m = all[i];
        ImGui::ColorButton(("##c" + std::to_string(i)).c_str(),
                           ImVec4(m.colour[0], m.colour[1], m.colour[2], 1.0f));
        tip("Material colour (linear RGB)");
        ImGui::SameLine();
        const std::string label = shown_name(m.name) + "##material" + std::to_string(i);
        if (ImGui::RadioButton(label.c_str(), settings_.material == static_cast<int>(i)))
            settings_.material = static_cast<int>(i);
        ui("material " + std::to_string(i),
           "Select: the Paint brush and the pour use this material; edit it below");
        ImGui::SameLine();
        ImGui::Text("%.0f / %.0f deg", m.repose_dry * 57.2957795, m.repose_wet * 57.2957795);
        tip("Angle of repose dry / with capillary moisture");
    }
    if (settings_.material < 0 || settings_.material >= static_cast<int>(all.size())) return;
    Material& m = all[static_cast<std::size_t>(settings_.material)];
    float dry = static_cast<float>(m.repose_dry * 57.2957795);
    float wet = static_cast<float>(m.repose_wet * 57.2957795);
    bool edited = false;
    // Typed values are clamped to the sliders' ranges, as everywhere (AlwaysClamp).
    ImGui::SliderFloat("Repose dry", &dry, 10.0f, 50.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    ui("Repose dry", "Steepest stable slope of the dry material");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderFloat("Repose moist", &wet, dry, 70.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
    ui("Repose moist",
       "Steepest stable slope with capillary moisture (the plateau before "
       "slumping)");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::ColorEdit3("Colour", m.colour, ImGuiColorEditFlags_Float);
    ui("Colour", "Albedo of the material (linear RGB)");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    ImGui::SliderFloat("Paint moisture", &m.default_moisture, 0.0f, 1.0f, "%.2f",
                       ImGuiSliderFlags_AlwaysClamp);
    ui("Paint moisture", "Saturation the Paint brush gives the sand it paints with this material");
    edited |= ImGui::IsItemDeactivatedAfterEdit();
    for (float& c : m.colour)
        c = std::clamp(c, 0.0f, 1.0f);  // an albedo: a typed 3 is white, not a light source
    m.repose_dry = static_cast<double>(std::clamp(dry, 10.0f, 50.0f)) / 57.2957795;
    m.repose_wet = static_cast<double>(std::clamp(std::max(wet, dry), dry, 70.0f)) / 57.2957795;
    // Applied when the control is released.
    if (edited) edit_material(settings_.material, m);
}

}  // namespace sandtin::editor
