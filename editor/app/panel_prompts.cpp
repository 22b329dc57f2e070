// The prompts: recover an autosave, unsaved edits, replace a file.

#include "app.hpp"

#include <algorithm>

#include "autosave_age.hpp"
#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::discard_prompt() {
    if (!pending_replacement_) return;
    ImGui::OpenPopup("Unsaved edits");
    if (ImGui::BeginPopupModal("Unsaved edits", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("The untitled scene has unsaved edits.");
        const std::string target = save_path().string();
        ImGui::Text("Save writes it to %s (the Scene field under File).", target.c_str());
        const std::string& then = pending_replacement_label_;
        // The answer is taken after the popup is closed and its frame's items are done with:
        // it may replace the document.
        std::optional<DiscardChoice> choice;
        if (ImGui::Button(("Save and " + then).c_str())) choice = DiscardChoice::Save;
        ui("unsaved/Save",
           "Save the scene to the path in the Scene field, then go on; if the\n"
           "save fails, the scene stays and the status line says why");
        ImGui::SameLine();
        if (ImGui::Button(("Discard and " + then).c_str())) choice = DiscardChoice::Discard;
        ui("unsaved/Discard", "The edits are lost");
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) choice = DiscardChoice::Cancel;
        ui("unsaved/Cancel", "Keep the scene open as it is");
        if (choice) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
        if (choice) answer_discard(*choice);
    }
}

std::optional<bool> App::answer_buttons(const PromptButton& yes, const PromptButton& no) {
    std::optional<bool> answer;
    if (ImGui::Button(yes.label)) answer = true;
    ui(std::string(yes.prompt) + "/" + yes.label, yes.tip);
    ImGui::SameLine();
    if (ImGui::Button(no.label)) answer = false;
    ui(std::string(no.prompt) + "/" + no.label, no.tip);
    if (answer) ImGui::CloseCurrentPopup();
    return answer;
}

void App::overwrite_prompt() {
    if (!pending_overwrite_) return;
    ImGui::OpenPopup("Replace file?");
    if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        const std::string target = pending_overwrite_->path.string();
        std::error_code ec;
        if (std::filesystem::exists(pending_overwrite_->path, ec))
            ImGui::Text("%s already exists; this scene is not that file.", target.c_str());
        if (find_autosave(pending_overwrite_->path))
            ImGui::Text("Its autosave holds edits that were never saved; it goes too.");
        const std::optional<bool> replace = answer_buttons(
            {"overwrite", "Replace", "Save this scene over that file"},
            {"overwrite", "Cancel", "Save nothing; type another name in the Scene field"});
        ImGui::EndPopup();
        if (replace) {
            const PendingOverwrite pending = std::move(*pending_overwrite_);
            pending_overwrite_.reset();
            if (!*replace)
                report("not saved: " + target + " exists (type another name in the Scene field)");
            else
                save(pending.path, pending.then);
        }
    }
}

std::string App::recovery_prompt_text() const {
    if (!recovery_for_) return {};
    std::string text = "An autosave newer than " + recovery_for_->string() + " exists";
    // Read each time the prompt is drawn: left open, it still tells the autosave's age.
    if (const auto written = autosave_written_at(*recovery_for_))
        text += ":\n" + autosave_age_text(*written, std::chrono::system_clock::now());
    return text + ".";
}

void App::recovery_prompt() {
    if (!recovery_for_) return;
    ImGui::OpenPopup("Recover autosave?");
    if (ImGui::BeginPopupModal("Recover autosave?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted(recovery_prompt_text().c_str());
        const std::optional<bool> recover = answer_buttons(
            {"recovery", "Recover", "Load the autosave; save to keep it"},
            {"recovery", "Discard", "Delete the autosave and keep the scene as saved"});
        ImGui::EndPopup();
        if (recover) answer_recovery(*recover);
    }
}

}  // namespace sandtin::editor
