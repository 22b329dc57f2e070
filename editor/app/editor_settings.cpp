#include "editor_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "recent_files.hpp"
#include "tool_palette.hpp"
#include "tools/falloff.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::editor {

namespace {

// One table drives both directions so a new field cannot be saved but not loaded; numeric
// fields carry their range (nullptr: any value of the type).
template <class F>
void fields(EditorSettings& s, F&& f) {
    f("tool_radius", s.tool_radius, &kToolRadiusRange);
    f("tool_depth", s.tool_depth, &kToolDepthRange);
    // Not "stroke_spacing": that key held metres in earlier versions, and is ignored now.
    f("stroke_spacing_ratio", s.stroke_spacing_ratio, &kStrokeSpacingRange);
    f("extrude", s.extrude, nullptr);
    f("follow_path", s.follow_path, nullptr);
    f("tool_angle", s.tool_angle, &kToolAngleRange);
    f("brush_strength", s.brush_strength, &kBrushStrengthRange);
    f("brush_blend", s.brush_blend, &kBrushBlendRange);
    f("brush_falloff", s.brush_falloff, nullptr);
    f("pour_volume", s.pour_volume, &kPourVolumeRange);
    f("material", s.material, nullptr);
    f("erosion_running", s.erosion_running, nullptr);
    f("erosion_steps", s.erosion_steps, &kErosionStepsRange);
    f("physics", s.physics, nullptr);
    f("simplify_tolerance", s.simplify_tolerance, &kSimplifyToleranceRange);
    f("relocation_radius", s.relocation_radius, &kRelocationRadiusRange);
    f("settle_margin", s.settle_margin, &kSettleMarginRange);
    f("slope_rule", s.slope_rule, nullptr);
    f("settle_fit_bends", s.settle_fit_bends, nullptr);
    f("overlay_wireframe", s.overlay_wireframe, nullptr);
    f("overlay_active", s.overlay_active, nullptr);
    f("overlay_thickness", s.overlay_thickness, nullptr);
    f("overlay_slope", s.overlay_slope, nullptr);
    f("overlay_water", s.overlay_water, nullptr);
    f("overlay_water_speed", s.overlay_water_speed, nullptr);
    f("overlay_sediment", s.overlay_sediment, nullptr);
    f("water_flowing", s.water_flowing, nullptr);
    f("water_erode", s.water_erode, nullptr);
    f("water_detail", s.water_detail, &kWaterDetailRange);
    f("water_rain", s.water_rain, &kWaterRainRange);
    f("water_evaporation", s.water_evaporation, &kWaterEvaporationRange);
    f("water_open_west", s.water_open_west, nullptr);
    f("water_open_east", s.water_open_east, nullptr);
    f("water_open_south", s.water_open_south, nullptr);
    f("water_open_north", s.water_open_north, nullptr);
    f("water_nozzle", s.water_nozzle, &kWaterNozzleRange);
    f("water_jet", s.water_jet, &kWaterJetRange);
    f("water_shower", s.water_shower, &kWaterShowerRange);
    f("contrast", s.contrast, &kContrastRange);
    f("vsync", s.vsync, nullptr);
    f("scene_size", s.scene_size, nullptr);
    f("recent_files", s.recent_files, nullptr);
    f("last_folder", s.last_folder, nullptr);
    f("file_dialog", s.file_dialog, nullptr);
}

std::string shown(const nlohmann::json& value) {
    std::string text = value.dump();
    return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

}  // namespace

double SettingRange::clamp(double value, double size) const {
    if (!(value >= lo_at(size))) return lo_at(size);  // also NaN
    return std::min(value, hi_at(size));
}

std::filesystem::path default_settings_path() {
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x != nullptr && *x != '\0')
        return std::filesystem::path(x) / "sandtin" / "editor.json";
    if (const char* h = std::getenv("HOME"); h != nullptr && *h != '\0')
        return std::filesystem::path(h) / ".config" / "sandtin" / "editor.json";
    return "sandtin-editor.json";
}

EditorSettings load_settings(const std::filesystem::path& path, std::string* problem) {
    std::ifstream in(path);
    if (!in) return {};
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
        if (!j.is_object()) throw std::runtime_error("not a JSON object");
    } catch (const std::exception& e) {
        if (problem != nullptr)
            *problem = "settings file " + path.string() + " ignored: " + e.what();
        return {};
    }
    std::vector<std::string> bad;
    EditorSettings s;
    // The size the file's lengths are for comes first: the ranges scale with it.
    if (const auto size = j.find("scene_size"); size != j.end()) {
        if (size->is_number() && size->get<double>() > 0.0 && std::isfinite(size->get<double>()) &&
            size->get<double>() <= 1e9)
            s.scene_size = size->get<double>();
        else
            bad.push_back("scene_size " + shown(*size) + " is not a size in metres (1 used)");
    }
    const EditorSettings defaults = s;
    fields(s, [&](const char* key, auto& value, const SettingRange* range) {
        using T = std::decay_t<decltype(value)>;
        const auto it = j.find(key);
        if (it == j.end() || std::string_view(key) == "scene_size") return;
        T loaded{};
        try {
            if constexpr (std::is_same_v<T, double>) {
                if (!it->is_number()) throw std::runtime_error("not a number");
            } else if constexpr (std::is_same_v<T, int>) {
                if (!it->is_number_integer()) throw std::runtime_error("not an integer");
            }
            loaded = it->get<T>();
        } catch (const std::exception&) {
            bad.push_back(std::string(key) + " " + shown(*it) + " has the wrong type");
            return;
        }
        if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
            const double v = static_cast<double>(loaded);
            if (range != nullptr && !range->contains(v, s.scene_size)) {
                char text[200];
                std::snprintf(text, sizeof(text), "%s %s is outside [%.6g, %.6g]", key,
                              shown(*it).c_str(), range->lo_at(s.scene_size),
                              range->hi_at(s.scene_size));
                bad.emplace_back(text);
                return;
            }
        }
        value = loaded;
    });
    if (const auto t = j.find("tool"); t != j.end() && t->is_string())
        s.tool = tool_named(t->get<std::string>()).value_or(0);
    if (!falloff_named(s.brush_falloff)) {
        bad.push_back("brush_falloff '" + s.brush_falloff + "' is unknown");
        s.brush_falloff = defaults.brush_falloff;
    }
    if (s.physics != "auto" && s.physics != "cpu" && s.physics != "gpu") {
        bad.push_back("physics '" + s.physics + "' is not auto, cpu or gpu");
        s.physics = defaults.physics;
    }
    if (s.slope_rule != "face" && s.slope_rule != "edge") {
        bad.push_back("slope_rule '" + s.slope_rule + "' is not face or edge");
        s.slope_rule = defaults.slope_rule;
    }
    if (s.file_dialog != "auto" && s.file_dialog != "native" && s.file_dialog != "imgui") {
        bad.push_back("file_dialog '" + s.file_dialog + "' is not auto, native or imgui");
        s.file_dialog = defaults.file_dialog;
    }
    // Files of earlier versions chose with a flag: true was a choice of the GPU, false the
    // default, which Auto now is.
    if (!j.contains("physics") && j.value("erosion_gpu", false) == true) s.physics = "gpu";
    // Entries a hand edit repeated or emptied, or beyond the ten the panel lists, are dropped
    // quietly: each is still a file the artist opened.
    s.recent_files = tidy_recent_files(s.recent_files);
    if (s.material < 0) {
        bad.push_back("material " + std::to_string(s.material) + " is not an index");
        s.material = defaults.material;
    }
    if (!bad.empty() && problem != nullptr) {
        std::string text = "settings file " + path.string() + ": ";
        for (std::size_t i = 0; i < bad.size(); ++i)
            text += (i > 0 ? "; " : "") + bad[i];
        *problem = text + " (the defaults are used for these)";
    }
    return s;
}

void save_settings(const std::filesystem::path& path, const EditorSettings& settings) {
    nlohmann::json j = nlohmann::json::object();
    EditorSettings copy = settings;
    fields(copy, [&](const char* key, auto& value, const SettingRange*) { j[key] = value; });
    j["tool"] = kTools[std::clamp(settings.tool, 0, kToolCount - 1)].label;
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    const std::string text = j.dump(2) + "\n";
    write_file_atomically(
        path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                            text.size()));
}

}  // namespace sandtin::editor
