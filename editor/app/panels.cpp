// The panels' frame: the main panel's sections, the status line, the Stats window, the
// prompts; and the tooltips every control has.

#include "app.hpp"

#include <algorithm>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "stats_lines.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::draw_panels() {
    take_native_dialog_result();
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // The status line (save and autosave failures, the terrain-scaling notice) has its own
    // window in the bottom-left corner, and the panel ends above it: when the panel is taller
    // than the window it scrolls, and the status line must never scroll out of sight with it.
    const float status_height = status_window_height();
    const float panel_bottom =
        std::max(display.y - kPanelMargin - status_height, 2.0f * kPanelMargin);
    ImGui::SetNextWindowPos(ImVec2(kPanelMargin, kPanelMargin), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(kPanelWidth, 0.0f),
                                        ImVec2(kPanelWidth, panel_bottom - kPanelMargin));
    ImGui::Begin("sandtin", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    // Controls take the width left of a column wide enough for the longest label; the layout
    // probe reports any control that still reaches past the panel's edge.
    ImGui::PushItemWidth(
        -(ImGui::CalcTextSize(kWidestLabel).x + ImGui::GetStyle().ItemInnerSpacing.x));
    const auto section = [&](const char* name, ImGuiTreeNodeFlags flags, void (App::*draw)()) {
        if (open_panels_) ImGui::SetNextItemOpen(*open_panels_);
        if (!ImGui::CollapsingHeader(name, flags)) return;
        layout_.begin(name);
        (this->*draw)();
        layout_.end();
    };
    section("File", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_file);
    section("Tools", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_tools);
    section("Materials", 0, &App::panel_materials);
    section("Erosion", ImGuiTreeNodeFlags_DefaultOpen, &App::panel_erosion);
    section("Water", 0, &App::panel_water);
    section("Haptics", 0, &App::panel_haptics);
    open_panels_.reset();
    ImGui::PopItemWidth();
    ImGui::End();
    status_window(status_height);
    stats_window();
    help_window();
    file_browser_window();
    recovery_prompt();
    discard_prompt();
    overwrite_prompt();
    job_window();
    settle_window();
}

float App::status_window_height() const {
    if (status_.empty()) return 0.0f;
    const ImGuiStyle& style = ImGui::GetStyle();
    const float wrap = kPanelWidth - 2.0f * style.WindowPadding.x;
    return ImGui::CalcTextSize(status_.c_str(), nullptr, false, wrap).y +
           2.0f * style.WindowPadding.y + kPanelMargin;
}

void App::status_window(float height) {
    if (status_.empty()) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(kPanelMargin, display.y - kPanelMargin), ImGuiCond_Always,
                            ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, height - kPanelMargin), ImGuiCond_Always);
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    ImGui::TextWrapped("%s", status_.c_str());
    layout_.item_visible("status");
    ImGui::End();
}

void App::tip(const char* text) {
    if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
    ImGui::SetTooltip("%s", text);
    widgets_.note_tooltip(text);
}

void App::ui(const std::string& name, const char* text) {
    widgets_.note(name);
    tip(text);
}

void App::stats_window() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
    // As wide as its widest line. The timing lines are made for their numbers at their widest
    // (stats_lines.hpp), so the window keeps its width as the numbers change, and fits them on
    // a machine however slow; every line as drawn is measured too, so nothing ever sticks out
    // (a large or high terrain's counts and volume, a large re-baked texel count).
    const StatsText text = stats_text();
    std::vector<std::string> measured(text.terrain.begin(), text.terrain.end());
    measured.insert(measured.end(), text.timing.begin(), text.timing.end());
    measured.push_back(text.normal_map);
    for (const std::string& line : widest_stats_timing_lines())
        measured.push_back(line);
    float widest = 0.0f;
    for (const std::string& line : measured)
        widest = std::max(widest, ImGui::CalcTextSize(line.c_str()).x);
    const float stats_width = widest + 2.0f * ImGui::GetStyle().WindowPadding.x;
    ImGui::SetNextWindowSize(ImVec2(stats_width, 0), ImGuiCond_Always);
    ImGui::Begin("Stats", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    layout_.begin("Stats");
    panel_stats(text);
    layout_.end();
    ImGui::End();
}

App::StatsText App::stats_text() const {
    StatsText text;
    text.terrain = stats_terrain_lines();
    text.timing =
        stats_timing_lines({StageTimes::median(times_.frame), StageTimes::median(times_.tool),
                            StageTimes::median(times_.physics), StageTimes::median(times_.mesh),
                            StageTimes::median(times_.upload), StageTimes::median(times_.bake),
                            StageTimes::median(times_.render)});
    char normal_map[96];
    std::snprintf(normal_map, sizeof(normal_map), "normal map %ux%u, re-baked %llu",
                  view_->normal_map() ? view_->normal_map()->grid().width : 0u,
                  view_->normal_map() ? view_->normal_map()->grid().height : 0u,
                  static_cast<unsigned long long>(view_->last_texels_baked()));
    text.normal_map = normal_map;
    return text;
}

std::array<std::string, 2> App::stats_terrain_lines() const {
    const Tin& t = doc_.tin();
    // Litres on the 1 m sandbox, cubic metres on a terrain a hundred times larger.
    const double size = settings_.scene_size;
    const DisplayUnit unit = volume_unit(1e-2 * size * size * size);
    char counts[96], volume[160];
    std::snprintf(counts, sizeof(counts), "%zu vertices, %zu triangles", t.vertex_count(),
                  t.triangle_count());
    std::snprintf(volume, sizeof(volume), "%zu constrained edges, volume %.3f %s",
                  t.constrained_edge_count(), t.volume() / unit.metres, unit.suffix);
    return {counts, volume};
}

void App::panel_stats(const StatsText& text) {
    for (const std::string& line : text.terrain)
        ImGui::TextUnformatted(line.c_str());
    ImGui::TextUnformatted(text.timing[0].c_str());
    ImGui::TextUnformatted(text.timing[1].c_str());
    ImGui::TextUnformatted(text.timing[2].c_str());
    tip("Median milliseconds per frame of each stage over the last 240 frames (bake: GPU mirror\n"
        "sync and normal-map re-bake of the changed rectangle)");
    ImGui::TextUnformatted(text.normal_map.c_str());
    tip("The baked normal map is re-baked only inside the rectangle the last change touched");
    std::vector<float> plot(times_.frame.begin(), times_.frame.end());
    ImGui::PlotLines("##frame", plot.data(), static_cast<int>(plot.size()), 0, "frame ms", 0.0f,
                     100.0f, ImVec2(0, 40));
    tip("Frame time over the last 240 frames (0-100 ms)");
}

}  // namespace sandtin::editor
