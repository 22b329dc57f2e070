// The Water panel: whether the water flows, the rain and evaporation over the whole terrain,
// the sides it leaves by, whether it erodes, the depth, speed and sediment overlays, Clear, and how
// much water there is. The Water tool (Tools panel, key 9) pours it; engine/water/live_water.hpp
// moves it.

#include "app.hpp"

#include <cstdio>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"

namespace sandtin::editor {

void App::panel_water() {
    ImGui::Checkbox("Flow", &settings_.water_flowing);
    ui("Flow",
       "Let the water run downhill (virtual pipes on the triangulation's edges); off, it\n"
       "stands where it is and the nozzle and rain still add to it");
    ImGui::SameLine();
    ImGui::Checkbox("Depth##overlay", &settings_.overlay_water);
    ui("Depth##overlay", "Water depth in false colour: pale cyan shallow, deep blue 5 cm or more");
    ImGui::SameLine();
    ImGui::Checkbox("Speed##overlay", &settings_.overlay_water_speed);
    ui("Speed##overlay",
       "How fast the water flows, in false colour on a log scale: 1 mm/s or less dark blue,\n"
       "then cyan (3 cm/s), yellow, and red at 1 m/s or more");
    ImGui::SameLine();
    ImGui::Checkbox("Sediment##overlay", &settings_.overlay_sediment);
    ui("Sediment##overlay",
       "The sand the water carries (with Erode on), in false colour: clear water pale blue,\n"
       "muddy brown at 5 % sand by volume");
    ImGui::Checkbox("Erode", &settings_.water_erode);
    ui("Erode",
       "The flowing water carries sand: it picks sand up where it runs fast down a slope and\n"
       "drops it where it slows, cutting channels and laying fans (gravel it carries stays\n"
       "gravel). Sand plus what the water holds is kept; rock is never eroded");
    range_slider("Detail", "", settings_.water_detail, kWaterDetailRange, settings_.scene_size,
                 "%.1f");
    ui("Detail",
       "Edges under the water longer than this are split, so that water on a coarse terrain\n"
       "(an imported elevation model) gets the triangles it flows through; 0 is off. The\n"
       "water's and the sand's volumes are kept, and the simplifier takes the vertices\n"
       "again once the ground is dry and planar");
    plain_slider("Rain", settings_.water_rain, kWaterRainRange, "%.0f mm/h");
    ui("Rain", "Rain on the whole terrain: 0 none, 10 steady rain, 50 a downpour, 500 a flood");
    plain_slider("Evaporation", settings_.water_evaporation, kWaterEvaporationRange, "%.0f mm/h");
    ui("Evaporation",
       "Water leaving every wet vertex (a warm day evaporates about 0.3 mm/h; more dries\n"
       "puddles quickly)");
    // Two sides to a row: four checkboxes and their names are wider than the panel.
    ImGui::TextUnformatted("Open sides");
    int placed = 0;
    const auto side = [&](const char* label, bool& open, const char* help) {
        if (placed++ % 2 == 1) ImGui::SameLine();
        ImGui::Checkbox(label, &open);
        ui(label, help);
    };
    side("West", settings_.water_open_west, "Water leaves over the west edge (x min)");
    side("East", settings_.water_open_east, "Water leaves over the east edge (x max)");
    side("South", settings_.water_open_south, "Water leaves over the south edge (y min)");
    side("North", settings_.water_open_north, "Water leaves over the north edge (y max)");
    if (ImGui::Button("Clear water")) {
        sculpting_.close_level(doc_);
        const double taken = doc_.water().clear();
        doc_.record_level("clear water");
        char text[96];
        std::snprintf(text, sizeof text, "cleared %.3g L of water", taken * 1000.0);
        report(text);
    }
    ui("Clear water", "Take all the water off the terrain (one undo level)");
    // Measured a few times a second: an undo or a load may have changed it.
    const auto now = Clock::now();
    if (now - water_summary_at_ > std::chrono::milliseconds(250)) {
        water_summary_ = doc_.water().measure();
        water_summary_at_ = now;
    }
    const WaterSummary& w = water_summary_;
    if (w.wet_vertices == 0) {
        ImGui::TextDisabled("dry");
    } else {
        ImGui::Text("%.3g L on %zu vertices, deepest %.1f mm%s", w.volume * 1000.0, w.wet_vertices,
                    w.max_depth * 1000.0, doc_.water().resting() ? ", at rest" : "");
    }
    tip("The water on the terrain: litres, the vertices under it, the deepest point");
}

}  // namespace sandtin::editor
