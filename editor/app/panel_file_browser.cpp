// The editor's own file browser (file_browser.hpp), drawn as a modal window: the folder with
// Up, the filter and the type-to-filter box, the folder's entries (folders first), the file
// name, and the button that picks. A file picked goes where the dialog's button sends it
// (App::apply_picked_file).

#include "app.hpp"

#include <algorithm>
#include <cfloat>
#include <cstdio>

#include "panel_layout.hpp"

namespace sandtin::editor {

namespace {

constexpr const char* kBrowserId = "###file-browser";

/// An ImGui text field over a std::string; true when Enter was pressed in it.
bool string_field(const char* id, const char* hint, std::string& value,
                  ImGuiInputTextFlags flags = ImGuiInputTextFlags_None) {
    char buffer[1024];
    std::snprintf(buffer, sizeof(buffer), "%s", value.c_str());
    const bool enter = ImGui::InputTextWithHint(id, hint, buffer, sizeof(buffer),
                                                flags | ImGuiInputTextFlags_EnterReturnsTrue);
    if (value != buffer) value = buffer;
    return enter;
}

}  // namespace

void App::file_browser_window() {
    if (!browser_.is_open()) return;
    const FileDialogRequest& request = browser_.request();
    const std::string title = request.title + kBrowserId;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const ImVec2 size(std::min(640.0f, display.x - 4.0f * kPanelMargin),
                      std::min(440.0f, display.y - 4.0f * kPanelMargin));
    ImGui::SetNextWindowSize(size, ImGuiCond_Always);
    ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::OpenPopup(title.c_str());
    if (!ImGui::BeginPopupModal(
            title.c_str(), nullptr,
            ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings))
        return;
    layout_.begin("File browser");
    const FileDialogKind kind = request.kind;
    std::optional<std::filesystem::path> picked = file_browser_header();
    if (browser_.is_open()) {
        // The list takes what the name row, the messages and the buttons leave.
        const ImGuiStyle& style = ImGui::GetStyle();
        // The name field, a line of text (the message, or the overwrite question) and a row
        // of buttons.
        const float footer = 2.0f * ImGui::GetFrameHeightWithSpacing() +
                             ImGui::GetTextLineHeightWithSpacing() + style.ItemSpacing.y;
        picked = file_browser_entries(std::max(ImGui::GetContentRegionAvail().y - footer,
                                               3.0f * ImGui::GetTextLineHeightWithSpacing()));
    }
    if (browser_.is_open()) file_browser_footer(picked);
    if (browser_.is_open() && !browser_.replacing() &&
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        browser_.close();
    layout_.end();
    if (!browser_.is_open()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    // Acted on once the popup is done with: the file may replace the document.
    if (picked) apply_picked_file(kind, *picked);
}

std::optional<std::filesystem::path> App::file_browser_header() {
    if (ImGui::Button("Up")) browser_.up();
    ui("browser/Up", "The folder that holds this one");
    ImGui::SameLine();
    std::string folder = browser_.folder().string();
    ImGui::SetNextItemWidth(-FLT_MIN);
    if (string_field("##folder", "folder", folder, ImGuiInputTextFlags_AutoSelectAll))
        browser_.navigate(folder);
    ui("browser/Folder", "The folder shown: type another and press Enter to go there");
    const FileDialogRequest& request = browser_.request();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.42f);
    if (ImGui::BeginCombo("##type", browser_.filter().label.c_str())) {
        for (std::size_t i = 0; i < request.filters.size(); ++i) {
            if (ImGui::Selectable(request.filters[i].label.c_str(), i == browser_.filter_index))
                browser_.filter_index = i;
        }
        ImGui::EndCombo();
    }
    ui("browser/Type", "Which files are listed: the ones this dialog takes, or all");
    ImGui::SameLine();
    const float hidden_width = ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
                               ImGui::CalcTextSize("Hidden").x;
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - hidden_width -
                            ImGui::GetStyle().ItemSpacing.x);
    // The box has the keys as the browser appears: typing filters at once.
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    std::optional<std::filesystem::path> picked;
    if (string_field("##filter", "type to filter", browser_.text))
        picked = browser_.accept_filter();
    ui("browser/Filter",
       "Only the names holding this text are listed; Enter picks the one file listed");
    ImGui::SameLine();
    ImGui::Checkbox("Hidden", &browser_.show_hidden);
    ui("browser/Hidden", "List the files and folders whose names begin with a dot");
    if (!browser_.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", browser_.error().c_str());
        ImGui::PopStyleColor();
        layout_.item_visible("browser/error");
    }
    return picked;
}

std::optional<std::filesystem::path> App::file_browser_entries(float height) {
    std::optional<std::filesystem::path> picked;
    ImGui::BeginChild("##entries", ImVec2(0.0f, height), true);
    const std::vector<FolderEntry> shown = browser_.visible();
    for (const FolderEntry& e : shown) {
        const std::string label = e.folder ? "[folder] " + e.name + "/" : e.name;
        if (ImGui::Selectable(label.c_str(), e.name == browser_.selected(),
                              ImGuiSelectableFlags_AllowDoubleClick)) {
            browser_.select(e);
            if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
                picked = browser_.activate(e);
                break;  // the listing may have changed under the loop
            }
        }
        ui("browser/entry/" + e.name,
           e.folder ? "Double-click to open this folder" : "Click to choose; double-click to pick");
    }
    if (shown.empty() && browser_.error().empty()) ImGui::TextDisabled("(nothing listed)");
    ImGui::EndChild();
    return picked;
}

void App::file_browser_footer(std::optional<std::filesystem::path>& picked) {
    const FileDialogRequest& request = browser_.request();
    ImGui::SetNextItemWidth(-FLT_MIN);
    const char* hint = request.saving ? "file name" : "file name (click one above)";
    if (string_field("##name", hint, browser_.name, ImGuiInputTextFlags_AutoSelectAll) && !picked)
        picked = browser_.accept();
    ui("browser/Name", request.saving ? "The file's name; without an extension it gets the "
                                        "first one of this dialog's list"
                                      : "The file to pick, in the folder shown");
    if (browser_.replacing()) {
        ImGui::Text("%s exists. Replace it?", browser_.replacing()->filename().string().c_str());
        if (ImGui::Button("Replace")) picked = browser_.answer_overwrite(true);
        ui("browser/Replace", "Write over the existing file");
        ImGui::SameLine();
        if (ImGui::Button("Keep it")) browser_.answer_overwrite(false);
        ui("browser/Keep", "Leave the file as it is and choose another name");
        return;
    }
    ImGui::TextUnformatted(browser_.message().c_str());
    if (ImGui::Button(request.action.c_str()) && !picked) picked = browser_.accept();
    ui("browser/OK", request.saving ? "Pick the file named above"
                                    : "Pick the file chosen above (or double-click it)");
    layout_.item_visible("browser/OK");
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
        browser_.close();
        picked.reset();
    }
    ui("browser/Cancel", "Close the dialog; nothing changes");
}

}  // namespace sandtin::editor
