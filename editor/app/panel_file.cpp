// The File panel: the scene, import, export, undo and redo.

#include "app.hpp"

#include <algorithm>

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
    if (ImGui::Button("Open")) replace_document("Open", [this] { open_reporting(); });
    ui("Open", "Open the .sandtin session named above (Ctrl+O)");
    ImGui::SameLine();
    if (ImGui::Button("Save")) request_save(save_path());
    ui("Save",
       "Save the scene to its file (Ctrl+S); the autosave is then removed. An untitled\n"
       "scene is saved under the path above");
    ImGui::SameLine();
    if (ImGui::Button("Save As")) request_save(path_buf_);
    ui("Save As", "Save the scene under the path above (asks before replacing another file)");
    if (path_field(widgets_, "Heightmap", "heightmap to import", import_buf_, sizeof(import_buf_),
                   "Import"))
        replace_document("Import", [this] { import_document(); });
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
}

}  // namespace sandtin::editor
