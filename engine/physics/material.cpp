#include "physics/material.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "util/json_document.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

double Material::repose(double moisture) const {
    const double m = std::clamp(moisture, 0.0, 1.0);
    auto pendular = [&](double x) {
        return repose_dry + (repose_wet - repose_dry) * (1.0 - std::exp(-x / moisture_scale));
    };
    if (m <= slurry_start || slurry_start >= 1.0) return pendular(m);
    const double at_start = pendular(slurry_start);
    return at_start + (repose_saturated - at_start) * (m - slurry_start) / (1.0 - slurry_start);
}

double Material::talus_slope(double moisture) const {
    return std::tan(repose(moisture));
}

MaterialTable::MaterialTable(std::vector<Material> materials) : materials_(std::move(materials)) {
    if (materials_.empty()) throw std::invalid_argument("material table is empty");
}

const Material& MaterialTable::at(std::uint16_t id) const {
    return id < materials_.size() ? materials_[id] : materials_.front();
}

MaterialTable MaterialTable::presets() {
    Material dry;  // the defaults are dry quartz sand
    Material moist = dry;
    moist.name = "moist_sand";
    moist.colour[0] = 0.55f;
    moist.colour[1] = 0.44f;
    moist.colour[2] = 0.30f;
    moist.haptic_stiffness = 1400.0;
    moist.haptic_friction = 0.75;
    moist.default_moisture = 0.25f;
    Material gravel;
    gravel.name = "gravel";
    gravel.repose_dry = 38.0 * kDegree;
    gravel.repose_wet = 40.0 * kDegree;
    gravel.moisture_scale = 0.1;
    gravel.slurry_start = 0.95;
    gravel.repose_saturated = 30.0 * kDegree;
    gravel.colour[0] = 0.45f;
    gravel.colour[1] = 0.43f;
    gravel.colour[2] = 0.40f;
    gravel.haptic_stiffness = 2500.0;
    gravel.haptic_friction = 0.8;
    return MaterialTable({dry, moist, gravel});
}

MaterialTable MaterialTable::load(const std::filesystem::path& path) {
    return from_json(read_json_document(path, "material file"), path.string());
}

MaterialTable MaterialTable::from_json(const nlohmann::json& j, const std::string& context) {
    if (!j.is_array() || j.empty())
        throw JsonInputError(context + ": expected a non-empty array of materials");
    std::vector<Material> out;
    for (std::size_t i = 0; i < j.size(); ++i) {
        JsonFields f(j[i], context + ": material " + std::to_string(i));
        Material m;
        m.name = f.text("name", m.name);
        m.repose_dry = f.in_range("repose_dry_deg", m.repose_dry / kDegree, 1.0, 89.0) * kDegree;
        m.repose_wet = f.in_range("repose_wet_deg", m.repose_wet / kDegree, 1.0, 89.0) * kDegree;
        m.moisture_scale = f.in_range("moisture_scale", m.moisture_scale, 1e-4, 10.0);
        m.slurry_start = f.in_range("slurry_start", m.slurry_start, 0.0, 1.0);
        m.repose_saturated =
            f.in_range("repose_saturated_deg", m.repose_saturated / kDegree, 1.0, 89.0) * kDegree;
        if (const nlohmann::json* c = f.get("colour")) {
            if (!c->is_array() || c->size() != 3)
                f.fail_field("colour", "must be [r, g, b] in [0, 1]");
            for (std::size_t k = 0; k < 3; ++k) {
                if (!(*c)[k].is_number() || (*c)[k].get<double>() < 0.0 ||
                    (*c)[k].get<double>() > 1.0) {
                    f.fail_field("colour", "must be [r, g, b] in [0, 1]");
                }
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

nlohmann::json MaterialTable::to_json() const {
    nlohmann::json list = nlohmann::json::array();
    for (const Material& m : materials_) {
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
    return list;
}

}  // namespace sandtin
