#include "editor_settings.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "tool_palette.hpp"
#include "tools/falloff.hpp"
#include "util/atomic_file.hpp"

namespace sandtin::editor {

namespace {

// One table drives both directions so a new field cannot be saved but not loaded.
template <class F>
void fields(EditorSettings& s, F&& f) {
    f("tool_radius", s.tool_radius);
    f("tool_depth", s.tool_depth);
    // Not "stroke_spacing": that key held metres in earlier versions, and is ignored now.
    f("stroke_spacing_ratio", s.stroke_spacing_ratio);
    f("extrude", s.extrude);
    f("follow_path", s.follow_path);
    f("tool_angle", s.tool_angle);
    f("brush_strength", s.brush_strength);
    f("brush_blend", s.brush_blend);
    f("brush_falloff", s.brush_falloff);
    f("pour_volume", s.pour_volume);
    f("material", s.material);
    f("erosion_running", s.erosion_running);
    f("erosion_steps", s.erosion_steps);
    f("erosion_gpu", s.erosion_gpu);
    f("simplify_tolerance", s.simplify_tolerance);
    f("relocation_radius", s.relocation_radius);
    f("settle_margin", s.settle_margin);
    f("overlay_wireframe", s.overlay_wireframe);
    f("overlay_active", s.overlay_active);
    f("overlay_thickness", s.overlay_thickness);
    f("overlay_slope", s.overlay_slope);
    f("contrast", s.contrast);
    f("vsync", s.vsync);
    f("scene_size", s.scene_size);
}

}  // namespace

std::filesystem::path default_settings_path() {
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x != nullptr && *x != '\0')
        return std::filesystem::path(x) / "sandtin" / "editor.json";
    if (const char* h = std::getenv("HOME"); h != nullptr && *h != '\0')
        return std::filesystem::path(h) / ".config" / "sandtin" / "editor.json";
    return "sandtin-editor.json";
}

EditorSettings load_settings(const std::filesystem::path& path, std::string* problem) {
    EditorSettings s;
    std::ifstream in(path);
    if (!in) return s;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (!j.is_object()) throw std::runtime_error("not a JSON object");
        EditorSettings loaded;
        fields(loaded, [&](const char* key, auto& value) {
            if (j.contains(key)) value = j.at(key).get<std::decay_t<decltype(value)>>();
        });
        if (const auto t = j.find("tool"); t != j.end() && t->is_string())
            loaded.tool = tool_named(t->get<std::string>()).value_or(0);
        if (!falloff_named(loaded.brush_falloff))
            throw std::runtime_error("brush_falloff '" + loaded.brush_falloff + "' is unknown");
        if (!(loaded.brush_blend >= 0.0 && loaded.brush_blend <= 1.0))
            throw std::runtime_error("brush_blend must lie in [0, 1]");
        if (!(loaded.stroke_spacing_ratio >= kMinStrokeSpacingRatio &&
              loaded.stroke_spacing_ratio <= kMaxStrokeSpacingRatio)) {
            static_assert(kMinStrokeSpacingRatio == 0.02 && kMaxStrokeSpacingRatio == 2.0,
                          "the message below names the range");
            throw std::runtime_error(
                "stroke_spacing_ratio must lie in [0.02, 2] (a fraction of the tool's radius)");
        }
        s = loaded;
    } catch (const std::exception& e) {
        if (problem != nullptr)
            *problem = "settings file " + path.string() + " ignored: " + e.what();
    }
    return s;
}

void save_settings(const std::filesystem::path& path, const EditorSettings& settings) {
    nlohmann::json j = nlohmann::json::object();
    EditorSettings copy = settings;
    fields(copy, [&](const char* key, auto& value) { j[key] = value; });
    j["tool"] = kTools[std::clamp(settings.tool, 0, kToolCount - 1)].label;
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    const std::string text = j.dump(2) + "\n";
    write_file_atomically(
        path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                            text.size()));
}

}  // namespace sandtin::editor
