#include "io/scene_materials.hpp"

#include <nlohmann/json.hpp>

#include "util/json_fields.hpp"

namespace sandtin {

std::string session_metadata(const MaterialTable& materials, const std::string& base) {
    nlohmann::json j = nlohmann::json::parse(base, nullptr, false);
    if (j.is_discarded() || !j.is_object()) j = nlohmann::json::object();
    j["editor"] = "sandtin-editor";
    j["materials"] = materials.to_json();
    return j.dump();
}

MaterialTable materials_or_presets(const std::string& metadata_json) {
    return materials_from_metadata(metadata_json).value_or(MaterialTable::presets());
}

std::optional<MaterialTable> materials_from_metadata(const std::string& metadata_json) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(metadata_json);
    } catch (const nlohmann::json::parse_error& e) {
        throw JsonInputError(std::string("session metadata: ") + e.what());
    }
    if (!j.is_object() || !j.contains("materials")) return std::nullopt;
    const nlohmann::json& list = j.at("materials");
    if (!list.is_array() || list.empty())
        throw JsonInputError("session metadata: 'materials' must be a non-empty array");
    return MaterialTable::from_json(list, "session metadata");
}

}  // namespace sandtin
