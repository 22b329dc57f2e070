// The Help window (F1): every key and mouse gesture, from the one list in shortcuts.hpp.

#include "app.hpp"

#include "panel_layout.hpp"

namespace sandtin::editor {

void App::help_window() {
    if (!help_open_) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    // As large as its table, within the window (it scrolls in a small one).
    ImGui::SetNextWindowSizeConstraints(
        ImVec2(0.0f, 0.0f),
        ImVec2(display.x - 2.0f * kPanelMargin, display.y - 2.0f * kPanelMargin));
    const bool shown =
        ImGui::Begin("Help: keys and mouse", &help_open_,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                         ImGuiWindowFlags_NoSavedSettings);
    if (shown) {
        layout_.begin("Help");
        // Fixed-fit columns: each as wide as its widest cell, and the window as wide as both.
        if (ImGui::BeginTable("keys", 2,
                              ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_BordersInnerV)) {
            ImGui::TableSetupColumn("Key or gesture");
            ImGui::TableSetupColumn("Action");
            ImGui::TableHeadersRow();
            for (const HelpRow& row : help_rows()) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                ImGui::TextUnformatted(row.keys.c_str());
                ImGui::TableSetColumnIndex(1);
                ImGui::TextUnformatted(row.action.c_str());
            }
            ImGui::EndTable();
        }
        if (ImGui::Button("Close")) help_open_ = false;
        ui("help/Close", "Close this list (F1 shows it again)");
        // Its last line: on screen means the whole list fits, or scrolls within the window.
        layout_.item_visible("help/Close");
        layout_.end();
    }
    ImGui::End();
}

}  // namespace sandtin::editor
