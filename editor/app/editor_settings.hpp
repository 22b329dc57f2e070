#pragma once
// Values the artist sets in the panels, persisted as JSON between sessions
// ($XDG_CONFIG_HOME/sandtin/editor.json, else ~/.config/sandtin/editor.json, or --settings).

#include "physics/talus_kernel.hpp"

#include <filesystem>
#include <string>

namespace sandtin::editor {

struct EditorSettings {
    int tool = 0;               ///< index into kTools; saved as the tool's label
    double tool_radius = 0.04;  ///< metres
    double tool_depth = 0.01;   ///< metres below the terrain ahead of the tool
    /// Stamps along a stroke, this fraction of the tool's radius apart (as a paint program's
    /// brush spacing): a big tool does not stamp dozens of times per width, nor a small one
    /// leave gaps. 0.25 is 1 cm for the default 4 cm tool.
    double stroke_spacing_ratio = 0.25;
    bool extrude = true;            ///< push displaced sand into a rim beside and ahead of the tool
    bool follow_path = true;        ///< tool heading follows the stroke
    double tool_angle = 0.0;        ///< degrees, when not following the path
    double brush_strength = 0.004;  ///< Raise/Lower: metres at the brush centre per dab
    double brush_blend = 0.5;       ///< Smooth/Flatten: fraction of the way to the target per dab
    std::string brush_falloff = "smooth";  ///< one of kFalloffNames (tools/falloff.hpp)
    double pour_volume = 2e-5;             ///< m³ per click / per 10 ms of drag
    int material = 0;                      ///< material painted and poured
    bool erosion_running = true;
    int erosion_steps = 20;              ///< relaxation iterations per frame
    bool erosion_gpu = false;            ///< relaxation on the GPU (GpuSandPhysics), else CPU
    double simplify_tolerance = 0.0005;  ///< metres
    double relocation_radius = 0.01;     ///< r_S, metres
    /// Flowing sand rests this fraction below its angle of repose (TalusParameters::
    /// settle_margin): a dig then comes to rest in thousands of iterations, not tens of
    /// thousands, so the terrain goes idle.
    double settle_margin = TalusParameters{}.settle_margin;
    bool overlay_wireframe = false;
    bool overlay_active = false;
    bool overlay_thickness = false;
    bool overlay_slope = false;
    double contrast = 0.5;  ///< strength of the height contrast curve, [0, 1]
    bool vsync = true;
    /// Metres: the size (larger domain side) of the terrain the lengths above are for. A
    /// terrain of another size rescales them (terrain_scale.hpp); 1 m is the default sandbox.
    double scene_size = 1.0;

    friend bool operator==(const EditorSettings&, const EditorSettings&) = default;
};

/// The range of stroke_spacing_ratio the panel offers and a settings file may hold.
inline constexpr double kMinStrokeSpacingRatio = 0.02;
inline constexpr double kMaxStrokeSpacingRatio = 2.0;

std::filesystem::path default_settings_path();
/// Missing file: defaults. Unreadable or invalid JSON: defaults, with `problem` set to why.
/// The tool is found by its label; an index (files of older versions, whose palette had
/// another order) or a label the palette no longer has falls back to the first tool.
EditorSettings load_settings(const std::filesystem::path& path, std::string* problem = nullptr);
/// Written atomically; throws std::runtime_error naming the path on failure.
void save_settings(const std::filesystem::path& path, const EditorSettings& settings);

}  // namespace sandtin::editor
