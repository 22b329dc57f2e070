#pragma once
// What the editor does with a file it is handed without a field to say so (dropped on the
// window, picked from the recent list): a scene is opened, a heightmap imported. Judged by the
// extension, case aside: the importer itself recognises formats by their content, but a
// dropped .txt must be refused with a clear message before anything is read.

#include <filesystem>
#include <string>

namespace sandtin::editor {

enum class FileKind { Scene, Heightmap, Other };

/// The extensions of the formats the heightmap importer reads (engine/io/heightmap_import.hpp):
/// PNG (16-bit grey or Terrain-RGB), OpenEXR, GeoTIFF and ESRI ASCII grid.
inline constexpr const char* kHeightmapExtensions[] = {".png", ".exr", ".tif", ".tiff", ".asc"};

/// The extension of a scene (engine/io/session_file.hpp).
inline constexpr const char* kSceneExtension = ".sandtin";

/// The extensions of the formats the exporter writes, chosen by the extension
/// (engine/io/export_terrain.hpp, export_format_for): meshes, then height maps. A test checks
/// each against the exporter.
inline constexpr const char* kExportExtensions[] = {".obj", ".ply", ".stl", ".gltf",
                                                    ".glb", ".png", ".exr"};

FileKind file_kind(const std::filesystem::path& path);

/// "a scene (.sandtin) or a heightmap (.png .exr .tif .tiff .asc)": what is accepted, for
/// the message that refuses anything else.
std::string accepted_files_text();

}  // namespace sandtin::editor
