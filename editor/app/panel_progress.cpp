// Progress bars, as plain functions of the state: the running job's (a modal with Cancel:
// while an import, an open or an export runs nothing else may change the document) and the
// erosion's settle to rest (a small window with Stop; the editor stays usable around it).

#include "app.hpp"

#include <algorithm>

#include "job_progress.hpp"
#include "panel_layout.hpp"

namespace sandtin::editor {

namespace {

/// The bar's width: room for a long stage line, whatever the job.
constexpr float kBarWidth = 360.0f;

/// Stage, bar with its percentage, elapsed and estimated time left.
void progress_body(const JobProgress& p) {
    ImGui::TextUnformatted(p.stage.c_str());
    ImGui::ProgressBar(static_cast<float>(p.fraction), ImVec2(kBarWidth, 0.0f),
                       percent_text(p.fraction).c_str());
    ImGui::TextUnformatted(job_times_text(p).c_str());
}

}  // namespace

void App::job_window() {
    if (!job_ && !job_popup_open_) return;
    // The popup's id stays "###job" whatever its title says.
    if (job_) ImGui::OpenPopup("###job");
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    const JobProgress p = job_ ? job_->progress() : JobProgress{};
    const std::string title = (job_ ? p.title : std::string("Working")) + "###job";
    if (!ImGui::BeginPopupModal(title.c_str(), nullptr,
                                ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
        if (!job_) job_popup_open_ = false;  // it ended before its popup was ever drawn
        return;
    }
    if (!job_) {
        // The job ended in the last frame: the modal lets go of the rest of the editor.
        ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        job_popup_open_ = false;
        return;
    }
    progress_body(p);
    ImGui::BeginDisabled(p.cancel_requested);
    if (ImGui::Button(p.cancel_requested ? "Cancelling...###Cancel" : "Cancel###Cancel"))
        cancel_job();
    ImGui::EndDisabled();
    ui("job/Cancel",
       "Stop (Escape). A cancelled import or open leaves the scene open before as it was;\n"
       "a cancelled export writes no file (an old one stays as it was)");
    ImGui::EndPopup();
    note_job_shown(p);
}

void App::settle_window() {
    if (!settle_.shown()) return;
    const JobProgress p = settle_.progress();
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float left = 2.0f * kPanelMargin + kPanelWidth;  // in the view, right of the panel
    ImGui::SetNextWindowPos(
        ImVec2(std::max(left, 0.5f * (display.x + left)), display.y - kPanelMargin),
        ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::Begin("Settling the sand###settle", nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoFocusOnAppearing |
                     ImGuiWindowFlags_NoSavedSettings);
    progress_body(p);
    if (ImGui::Button("Stop")) stop_settling();
    ui("settle/Stop",
       "Pause the erosion here: what has settled so far stays, as one undo level.\n"
       "Run goes on from there. The bar counts the vertices that came to rest, not time");
    ImGui::End();
}

}  // namespace sandtin::editor
