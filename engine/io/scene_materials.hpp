#pragma once
// The scene's material table travels in the session file's metadata (Session::metadata_json),
// as {"editor": "sandtin-editor", "materials": [...]} with the entries in the format of
// assets/materials/presets.json (angles in degrees), so a scene reopens with the materials it
// was sculpted with, including the artist's edits in the Materials panel, and `sandtin run`
// erodes and paints it with them.

#include <optional>
#include <string>

#include "physics/material.hpp"

namespace sandtin {

/// The metadata object for a session holding `materials`, keeping every other key of the
/// metadata the scene was opened with (`base`, e.g. the import record with its georeference
/// and grid, which exports use): an editor save must not drop what other tools wrote.
std::string session_metadata(const MaterialTable& materials, const std::string& base = "{}");

/// The material table stored in a session's metadata; nothing when the metadata has none
/// (files written before the editor saved materials, or by other tools). Throws
/// JsonInputError naming the entry and field for invalid metadata.
std::optional<MaterialTable> materials_from_metadata(const std::string& metadata_json);

/// The material table a scene was saved with, or the presets when its metadata holds none:
/// what the editor opens it with, `sandtin run` erodes it with and `sandtin export` colours it
/// with. Throws as materials_from_metadata.
MaterialTable materials_or_presets(const std::string& metadata_json);

}  // namespace sandtin
