// The Tools panel: the palette and the current tool's sliders.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::panel_tools() {
    // The palette by kind, three to a row after a column of headings. A column is as wide as
    // the widest tool's button, so that no label runs into the next button.
    const ImGuiStyle& style = ImGui::GetStyle();
    const std::array<const char*, 3> headings{"Stamps", "Sand", "Brushes"};
    float heading_width = 0.0f;
    for (const char* h : headings)
        heading_width = std::max(heading_width, ImGui::CalcTextSize(h).x);
    float button_width = 0.0f;
    for (int i = 0; i < kToolCount; ++i) {
        button_width = std::max(button_width, ImGui::GetFrameHeight() + style.ItemInnerSpacing.x +
                                                  ImGui::CalcTextSize(kTools[i].label).x);
    }
    const float left = heading_width + style.ItemSpacing.x;
    const float column = std::max(button_width + style.ItemSpacing.x,
                                  (ImGui::GetContentRegionAvail().x - left) / 3.0f);
    const auto group = [&](const char* heading, auto member) {
        int placed = 0;
        for (int i = 0; i < kToolCount; ++i) {
            if (!member(kTools[i])) continue;
            if (placed % 3 == 0) ImGui::TextDisabled("%s", placed == 0 ? heading : "");
            ImGui::SameLine(left + column * static_cast<float>(placed % 3));
            if (ImGui::RadioButton(kTools[i].label, settings_.tool == i)) pick_tool(i);
            ui(kTools[i].label, kTools[i].help);
            ++placed;
        }
    };
    group(headings[0], [](const ToolEntry& t) { return t.kind == ToolKind::Stamp; });
    group(headings[1], [](const ToolEntry& t) {
        return t.kind == ToolKind::Pour || t.kind == ToolKind::Remove ||
               t.kind == ToolKind::Water || t.kind == ToolKind::Rain;
    });
    group(headings[2], [](const ToolEntry& t) { return t.kind == ToolKind::Brush; });

    tool_sliders();
}

void App::tool_sliders() {
    const ToolEntry& tool = kTools[settings_.tool];
    const double size = settings_.scene_size;
    // Only the sliders that act on this tool: Size does not size the box, rake, letter or
    // foot, and Depth acts on stamps and on the haptic pen only.
    const bool round_stamp = tool.kind == ToolKind::Stamp && sized_by_slider(cursor_tool().spec());
    const ToolSliders sliders = sliders_for(tool, round_stamp, haptics_ != nullptr);
    if (sliders.size) {
        range_slider("Size", "", settings_.tool_radius, kToolRadiusRange, size, "%.1f");
        ui("Size", "Radius of round tools (circle, ball), brushes and the pour");
    } else if (tool.kind == ToolKind::Stamp) {
        stamp_size_readout();  // the nozzle has no size to show
    }
    if (sliders.depth) {
        range_slider("Depth", "", settings_.tool_depth, kToolDepthRange, size, "%.1f");
        ui("Depth",
           "How deep a stamp tool presses below the terrain ahead of it, and how deep\n"
           "the haptic pen's tip rests in the sand");
    }
    switch (tool.kind) {
        case ToolKind::Stamp: {
            plain_slider("Spacing", settings_.stroke_spacing_ratio, kStrokeSpacingRange,
                         "%.0f %% of size", 100.0, ImGuiSliderFlags_Logarithmic);
            ui("Spacing",
               "Distance between stamps along a stroke, as a share of the tool's\n"
               "radius (independent of frame rate)");
            ImGui::Checkbox("Extrude", &settings_.extrude);
            ui("Extrude",
               "Push the displaced sand into a rim beside and ahead of the tool (volume "
               "conserved).");
            ImGui::SameLine();
            ImGui::Checkbox("Follow path", &settings_.follow_path);
            ui("Follow path",
               "Turn the tool with the stroke direction; otherwise use the fixed orientation");
            ImGui::BeginDisabled(settings_.follow_path);
            plain_slider("Orientation", settings_.tool_angle, kToolAngleRange, "%.0f deg");
            ImGui::EndDisabled();
            ui("Orientation",
               "Tool heading when it does not follow the path (turn Follow path off to set it)");
            break;
        }
        case ToolKind::Pour:
        case ToolKind::Remove: {
            range_slider("Pour", "", settings_.pour_volume, kPourVolumeRange, size, "%.0f");
            ui("Pour",
               "Sand poured or removed per dab. A click is one dab; a drag adds one\n"
               "every quarter of the Size along the stroke, however fast the mouse\n"
               "moves; holding the button still adds four dabs a second (4 x this\n"
               "volume per second)");
            break;
        }
        case ToolKind::Water: {
            range_slider("Flow", "/s", settings_.water_nozzle, kWaterNozzleRange, size, "%.1f");
            ui("Flow",
               "Water the nozzle gives per second while the button is held (1 L = 1000 cm3).\n"
               "The water then runs as the Water panel says");
            range_slider("Jet", "", settings_.water_jet, kWaterJetRange, size, "%.1f");
            ui("Jet",
               "Radius of the jet: the water lands on the terrain within it, the same depth\n"
               "everywhere. 0 pours it all on the nearest vertex");
            break;
        }
        case ToolKind::Rain: {
            plain_slider("Rain", settings_.water_shower, kWaterShowerRange, "%.0f mm/h");
            ui("Rain",
               "Rain on the disc under the cursor while the button is held (mm of water an\n"
               "hour: 1000 mm/h is 1 L per m2 every 3.6 s). The Water panel's rain falls on\n"
               "the whole terrain besides");
            break;
        }
        case ToolKind::Brush: {
            if (tool.brush == BrushKind::Raise || tool.brush == BrushKind::Lower) {
                range_slider("Height", "/dab", settings_.brush_strength, kBrushStrengthRange, size,
                             "%.1f");
                ui("Height", "Height a Raise or Lower dab adds or takes at its centre");
            } else if (tool.brush == BrushKind::Smooth || tool.brush == BrushKind::Flatten ||
                       tool.brush == BrushKind::Weather) {
                plain_slider("Strength", settings_.brush_blend, kBrushBlendRange, "%.2f");
                ui("Strength",
                   "Fraction of the way to the smooth surface (Smooth) or to the stroke's\n"
                   "starting level (Flatten) that one dab goes at the brush centre; for\n"
                   "Weather, the fraction of a full weathering step (a tenth of the local\n"
                   "edge length at the sharpest crest)");
            }
            if (tool.brush != BrushKind::PaintMaterial) {
                int falloff = static_cast<int>(
                    falloff_named(settings_.brush_falloff).value_or(Falloff::Smooth));
                if (ImGui::Combo("Falloff", &falloff, kFalloffNames.data(),
                                 static_cast<int>(kFalloffNames.size())))
                    settings_.brush_falloff = kFalloffNames[static_cast<std::size_t>(falloff)];
                ui("Falloff",
                   "How a dab's effect fades from its centre to its rim: constant, linear,\n"
                   "smooth (flat centre, soft rim) or gaussian (1 % at the rim)");
            } else if (settings_.material >= 0 &&
                       settings_.material < static_cast<int>(doc_.materials().size())) {
                ImGui::TextWrapped(
                    "Paints %s (pick the material under Materials)",
                    shown_name(
                        doc_.materials().all()[static_cast<std::size_t>(settings_.material)].name)
                        .c_str());
            }
            break;
        }
    }
}

void App::stamp_size_readout() {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Vec2 p : cursor_tool().shape().inner) {
        x0 = std::min(x0, p.x);
        y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x);
        y1 = std::max(y1, p.y);
    }
    // The unit the Size slider shows on this terrain.
    const DisplayUnit unit = length_unit(0.15 * settings_.scene_size);
    ImGui::LabelText("Size", "%.1f x %.1f %s", (x1 - x0) / unit.metres, (y1 - y0) / unit.metres,
                     unit.suffix);
    ui("Size",
       "This tool's own size (its shape, scaled to the terrain); the Size slider sets\n"
       "the radius of round tools only");
}

}  // namespace sandtin::editor
