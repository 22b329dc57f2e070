// The Erosion panel: Run, the solver, its parameters and the overlays.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::panel_erosion() {
    // "Run###Run": one control, whatever it says, for the scripts and the test that find it.
    if (ImGui::Button(erosion_runs() ? "Pause###Run" : "Run###Run")) toggle_erosion();
    ui("Run",
       "Run or pause talus relaxation. An opened or imported scene waits for Run, so\n"
       "an elevation model does not melt as it appears. A stroke and the settling it\n"
       "causes are one undo level");
    ImGui::SameLine();
    // Wrapped: "paused for the opened scene: Run lets it settle" is wider than the panel (it
    // showed cut off when a scene opened with the erosion running).
    ImGui::TextWrapped("%s", erosion_status().c_str());
    tip("Paused, at rest, or sliding with the number of vertices the relaxation still looks at");
    if (ImGui::Button("Settle exactly")) settle_exactly();
    ui("Settle exactly",
       "Bring all the sand to rest at once, exactly at its angle of repose: the surface\n"
       "nearest this one on which no triangle is steeper than its sand stands, with the same\n"
       "volume (the physical rest of a collapse; the relaxation leaves it rippled). Runs under\n"
       "a bar with Cancel, seconds for 10^4 vertices; one undo level");
    ImGui::SameLine();
    ImGui::Checkbox("Fit toe and crest", &settings_.settle_fit_bends);
    ui("Fit toe and crest",
       "Settle exactly puts vertices on the settled surface's bends, the toe of a pile and the\n"
       "crest of a cut, and settles again: the bend then lies on an edge instead of being\n"
       "smeared over the triangles across it (a thin layer a few millimetres past the toe).\n"
       "Three to four times the time; the vertices and the heights are one undo level");
    ImGui::SliderInt("Steps/frame", &settings_.erosion_steps,
                     static_cast<int>(kErosionStepsRange.lo),
                     static_cast<int>(kErosionStepsRange.hi), "%d", ImGuiSliderFlags_AlwaysClamp);
    ui("Steps/frame", "Relaxation iterations per frame");
    // Auto, CPU or GPU; Auto says where it resolved on this device.
    const bool on_gpu = doc_.solver().device() == SolverDevice::Gpu;
    const std::string auto_label = std::string("Auto (") + (on_gpu ? "GPU" : "CPU") + ")###Auto";
    std::string choice = settings_.physics;
    if (ImGui::RadioButton(auto_label.c_str(), choice == "auto")) choice = "auto";
    ui("Auto",
       "Relaxation on the GPU when the Vulkan device is a hardware GPU, on the CPU on a\n"
       "software device (lavapipe), where the CPU solver is faster and exact");
    ImGui::SameLine();
    if (ImGui::RadioButton("CPU", choice == "cpu")) choice = "cpu";
    ui("CPU", "Relaxation on the CPU: the reference solver (sequential active list)");
    ImGui::SameLine();
    if (ImGui::RadioButton("GPU", choice == "gpu")) choice = "gpu";
    ui("GPU",
       "Relaxation on the GPU (Jacobi, two phases over the active list); the heights are read\n"
       "back into the terrain after every batch, so tools, saves and undo see them");
    if (choice != settings_.physics) {
        sculpting_.close_level(doc_);
        settings_.physics = choice;
        attach_solver(true);
    }
    range_slider("r_S", "", settings_.relocation_radius, kRelocationRadiusRange,
                 settings_.scene_size, "%.1f");
    ui("r_S", "Relocation radius: material never jumps farther; longer edges are split");
    ImGui::TextUnformatted("Repose on");
    ImGui::SameLine();
    if (ImGui::RadioButton("Faces", settings_.slope_rule != "edge")) set_slope_rule("face");
    ui("Faces",
       "At rest no triangle is steeper than its sand's angle of repose (the surface itself)");
    ImGui::SameLine();
    if (ImGui::RadioButton("Edges", settings_.slope_rule == "edge")) set_slope_rule("edge");
    ui("Edges",
       "The seeds' rule: at rest no edge is steeper than repose; a triangle can still be\n"
       "up to about twice as steep as its sand stands (shown red by the Slope overlay)");
    plain_slider("Settle margin (%)", settings_.settle_margin, kSettleMarginRange, "%.1f", 100.0);
    ui("Settle margin",
       "Sand that slides comes to rest this much below its angle of repose (the dynamic\n"
       "angle is 1-3 degrees lower). 0 = the seeds' rule: a dug slope creeps for much longer");
    if (range_slider("Simplify", "", settings_.simplify_tolerance, kSimplifyToleranceRange,
                     settings_.scene_size, "%.2f"))
        doc_.context().settings.simplify.tolerance = settings_.simplify_tolerance;
    ui("Simplify",
       "Vertices within this distance of a common plane with their neighbours are removed");
    ImGui::Checkbox("Wireframe", &settings_.overlay_wireframe);
    ui("Wireframe", "Show the triangulation; constrained edges (tool rims) in magenta");
    ImGui::SameLine();
    ImGui::Checkbox("Active", &settings_.overlay_active);
    ui("Active", "Highlight vertices that moved in the last erosion step");
    ImGui::Checkbox("Sand depth", &settings_.overlay_thickness);
    ui("Sand depth", "Sand thickness above bedrock: blue thin, yellow 5 cm or more");
    ImGui::SameLine();
    ImGui::Checkbox("Slope", &settings_.overlay_slope);
    ui("Slope",
       "Each triangle's slope against the angle of repose of its sand: green below 80 %, "
       "yellow up to repose, red steeper (the faces `sandtin info` counts as steep)");
    plain_slider("Contrast", settings_.contrast, kContrastRange, "%.3f");
    ui("Contrast", "Strength of the height contrast curve (histogram stretch)");
    if (ImGui::Checkbox("VSync", &settings_.vsync)) window_->recreate_swapchain(settings_.vsync);
    ui("VSync", "Wait for the display's refresh when presenting");
}

}  // namespace sandtin::editor
