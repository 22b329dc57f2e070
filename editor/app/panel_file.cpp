// The File panel: the scene, import, export, undo and redo, and the recent files.

#include "app.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

#include "panel_layout.hpp"
#include "panel_widgets.hpp"
#include "terrain_scale.hpp"
#include "tool_palette.hpp"

namespace sandtin::editor {

void App::panel_file() {
    ImGui::InputText("Scene", path_buf_, sizeof(path_buf_));
    ui("Scene", "Path used by Open, Save As and Ctrl+S when the scene has no file yet");
    if (ImGui::Button("New")) replace_document("New", [this] { new_document(); });
    ui("New", "Start a new 1 m x 1 m sandbox with dunes (Ctrl+N)");
    ImGui::SameLine();
    if (ImGui::Button("Open")) replace_document("Open", [this] { open_reporting(path_buf_); });
    ui("Open", "Open the .sandtin session named above (Ctrl+O)");
    ImGui::SameLine();
    if (ImGui::Button("Save")) request_save(save_path());
    ui("Save",
       "Save the scene to its file (Ctrl+S); the autosave is then removed. An untitled\n"
       "scene is saved under the path above");
    ImGui::SameLine();
    if (ImGui::Button("Save As")) request_save(path_buf_);
    ui("Save As", "Save the scene under the path above (asks before replacing another file)");
    file_dialog_buttons();
    if (path_field(widgets_, "Heightmap", "heightmap to import", import_buf_, sizeof(import_buf_),
                   "Import"))
        replace_document("Import", [this] { import_document(import_buf_); });
    ui("Import",
       "Import the heightmap named on the left as a new, untitled scene (an error-bounded\n"
       "TIN): PNG (16-bit or Terrain-RGB), EXR, GeoTIFF or ESRI ASCII grid");
    if (path_field(widgets_, "Export path", "file to export to", export_buf_, sizeof(export_buf_),
                   "Export"))
        export_reporting(export_buf_);
    ui("Export",
       "Write the terrain to the file named on the left: a mesh (.obj .ply .stl .gltf .glb)\n"
       "or a heightmap (.png .exr); the extension picks the format");
    ImGui::BeginDisabled(!doc_.undo_log().can_undo());
    if (ImGui::Button("Undo")) undo();
    ImGui::EndDisabled();
    ui("Undo",
       "Undo the last stroke with its settling, brush, pour, erosion run or material\n"
       "edit (Ctrl+Z)");
    ImGui::SameLine();
    ImGui::BeginDisabled(!doc_.undo_log().can_redo());
    if (ImGui::Button("Redo")) redo();
    ImGui::EndDisabled();
    ui("Redo", "Redo (Ctrl+Y)");
    ImGui::SameLine();
    ImGui::TextUnformatted(
        undo_levels_text(doc_.undo_log().levels(), doc_.history().bytes()).c_str());
    recent_files_list();
}

void App::file_dialog_buttons() {
    // Two a row, each half the row: they fit the panel whatever its scroll bar takes.
    const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
    struct DialogButton {
        const char* label;
        FileDialogKind kind;
        const char* tip;
    };
    static constexpr DialogButton kButtons[] = {
        {"Open...", FileDialogKind::Open, "Choose a scene (.sandtin) to open"},
        {"Save As...", FileDialogKind::SaveAs,
         "Choose where to save the scene (asks before replacing another file)"},
        {"Import...", FileDialogKind::Import,
         "Choose a heightmap to import as a new, untitled scene"},
        {"Export...", FileDialogKind::Export,
         "Choose a file to export the terrain to (the extension picks the format)"},
    };
    const bool busy = file_dialog_open();
    for (std::size_t i = 0; i < std::size(kButtons); ++i) {
        if (i % 2 == 1) ImGui::SameLine();
        ImGui::BeginDisabled(busy);
        if (ImGui::Button(kButtons[i].label, ImVec2(half, 0.0f)))
            show_file_dialog(kButtons[i].kind);
        ImGui::EndDisabled();
        ui(kButtons[i].label, busy ? "A file dialog is open: answer it first" : kButtons[i].tip);
    }
}

void App::recent_files_list() {
    if (settings_.recent_files.empty()) return;
    ImGui::Separator();
    ImGui::TextUnformatted("Recent files");
    std::optional<std::size_t> remove;
    std::optional<std::pair<std::filesystem::path, FileKind>> chosen;
    const ImGuiStyle& style = ImGui::GetStyle();
    for (std::size_t i = 0; i < settings_.recent_files.size(); ++i) {
        const std::filesystem::path path = settings_.recent_files[i];
        const std::string name = "recent/" + std::to_string(i);
        std::error_code ec;
        const bool exists = std::filesystem::is_regular_file(path, ec);
        const std::string label = path.filename().string() + (exists ? "" : " (missing)");
        ImGui::PushID(static_cast<int>(i));
        // Only scenes and imported heightmaps are listed: whatever is not a scene was imported
        // (the importer reads formats by their content, whatever their extension).
        const FileKind kind =
            file_kind(path) == FileKind::Scene ? FileKind::Scene : FileKind::Heightmap;
        if (exists) {
            if (ImGui::Selectable(label.c_str())) chosen = {path, kind};
            const std::string text =
                (kind == FileKind::Scene ? "Open " : "Import ") + path.string();
            ui(name, text.c_str());
        } else {
            // Greyed, with room on its row for the button that takes it off the list.
            const float remove_width =
                ImGui::CalcTextSize("Remove").x + 2.0f * style.FramePadding.x;
            const float width =
                ImGui::GetContentRegionAvail().x - remove_width - style.ItemSpacing.x;
            ImGui::BeginDisabled();
            ImGui::Selectable(label.c_str(), false, 0, ImVec2(width, 0.0f));
            ImGui::EndDisabled();
            const std::string text = path.string() + " no longer exists";
            ui(name, text.c_str());
            ImGui::SameLine();
            if (ImGui::SmallButton("Remove")) remove = i;
            ui(name + "/Remove", "Take the missing file off the list");
        }
        ImGui::PopID();
    }
    // Acted on after the list is drawn: both change the list being walked.
    if (remove) {
        settings_.recent_files.erase(settings_.recent_files.begin() +
                                     static_cast<std::ptrdiff_t>(*remove));
    }
    if (chosen) open_or_import(chosen->first, chosen->second);
}

}  // namespace sandtin::editor
