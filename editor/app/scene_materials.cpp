#include "scene_materials.hpp"

#include <numbers>

#include <nlohmann/json.hpp>

#include "util/json_fields.hpp"

namespace sandtin::editor {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

std::string session_metadata(const MaterialTable& materials) {
    nlohmann::json list = nlohmann::json::array();
    for (const Material& m : materials.all()) {
        list.push_back({{"name", m.name},
                        {"repose_dry_deg", m.repose_dry / kDegree},
                        {"repose_wet_deg", m.repose_wet / kDegree},
                        {"moisture_scale", m.moisture_scale},
                        {"slurry_start", m.slurry_start},
                        {"repose_saturated_deg", m.repose_saturated / kDegree},
                        {"colour", {m.colour[0], m.colour[1], m.colour[2]}},
                        {"haptic_stiffness", m.haptic_stiffness},
                        {"haptic_friction", m.haptic_friction},
                        {"default_moisture", m.default_moisture}});
    }
    return nlohmann::json{{"editor", "sandtin-editor"}, {"materials", list}}.dump();
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
    // The same fields and ranges as MaterialTable::load (tests compare the two on the presets).
    std::vector<Material> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        JsonFields f(list[i], "session metadata: material " + std::to_string(i));
        Material m;
        m.name = f.text("name", m.name);
        m.repose_dry = f.in_range("repose_dry_deg", m.repose_dry / kDegree, 1.0, 89.0) * kDegree;
        m.repose_wet = f.in_range("repose_wet_deg", m.repose_wet / kDegree, 1.0, 89.0) * kDegree;
        m.moisture_scale = f.in_range("moisture_scale", m.moisture_scale, 1e-4, 10.0);
        m.slurry_start = f.in_range("slurry_start", m.slurry_start, 0.0, 1.0);
        m.repose_saturated =
            f.in_range("repose_saturated_deg", m.repose_saturated / kDegree, 1.0, 89.0) * kDegree;
        if (const nlohmann::json* c = f.get("colour")) {
            if (!c->is_array() || c->size() != 3) f.fail_field("colour", "must be [r, g, b]");
            for (std::size_t k = 0; k < 3; ++k) {
                if (!(*c)[k].is_number() || (*c)[k].get<double>() < 0.0 ||
                    (*c)[k].get<double>() > 1.0)
                    f.fail_field("colour", "must be [r, g, b] in [0, 1]");
                m.colour[k] = (*c)[k].get<float>();
            }
        }
        m.haptic_stiffness = f.in_range("haptic_stiffness", m.haptic_stiffness, 0.0, 1e6);
        m.haptic_friction = f.in_range("haptic_friction", m.haptic_friction, 0.0, 10.0);
        m.default_moisture =
            static_cast<float>(f.in_range("default_moisture", m.default_moisture, 0.0, 1.0));
        f.reject_unknown();
        out.push_back(std::move(m));
    }
    return MaterialTable(std::move(out));
}

}  // namespace sandtin::editor
