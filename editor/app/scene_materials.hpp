#pragma once
// The scene's material table travels in the session file's metadata (Session::metadata_json),
// as {"editor": "sandtin-editor", "materials": [...]} with the entries in the format of
// assets/materials/presets.json (angles in degrees), so a scene reopens with the materials it
// was sculpted with, including the artist's edits in the Materials panel.

#include <optional>
#include <string>

#include "physics/material.hpp"

namespace sandtin::editor {

/// The metadata object for a session holding `materials`.
std::string session_metadata(const MaterialTable& materials);

/// The material table stored in a session's metadata; nothing when the metadata has none
/// (files written before the editor saved materials, or by other tools). Throws
/// JsonInputError naming the entry and field for invalid metadata.
std::optional<MaterialTable> materials_from_metadata(const std::string& metadata_json);

}  // namespace sandtin::editor
