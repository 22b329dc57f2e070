#pragma once
// Values the artist sets in the panels, persisted as JSON between sessions
// ($XDG_CONFIG_HOME/sandtin/editor.json, else ~/.config/sandtin/editor.json, or --settings).

#include "physics/talus_kernel.hpp"

#include <filesystem>
#include <string>
#include <vector>

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
    int erosion_steps = 20;  ///< relaxation iterations per frame
    /// Where the relaxation runs: "auto" (the GPU when the Vulkan device is a hardware GPU,
    /// the CPU on a software device such as lavapipe), "cpu" or "gpu".
    std::string physics = "auto";
    double simplify_tolerance = 0.0005;  ///< metres
    double relocation_radius = 0.01;     ///< r_S, metres
    /// Flowing sand rests this fraction below its angle of repose (TalusParameters::
    /// settle_margin): a dig then comes to rest in thousands of iterations, not tens of
    /// thousands, so the terrain goes idle.
    double settle_margin = TalusParameters{}.settle_margin;
    /// What the relaxation holds at repose (SlopeRule): "face", every triangle's gradient (the
    /// default), or "edge", every edge's slope (the seeds' rule, for comparison).
    std::string slope_rule = "face";
    /// Settle exactly fits the rest surface's bends, the toe and the crest, with one round of
    /// vertices on them and a second projection (physics/settle_fitted_to_kinks.hpp): sharper
    /// toes for three to four times the time.
    bool settle_fit_bends = false;
    bool overlay_wireframe = false;
    bool overlay_active = false;
    bool overlay_thickness = false;
    bool overlay_slope = false;
    bool overlay_water = false;        ///< water depth in false colour
    bool overlay_water_speed = false;  ///< how fast the water flows, in false colour
    bool overlay_sediment = false;     ///< the sand the water carries, in false colour
    /// The Water panel (engine/water/live_water.hpp): the water flows (else it stands still),
    /// rain on the whole terrain and evaporation (mm/h), the sides water leaves by, and the
    /// Water tool's nozzle (m³ per second on the 1 m sandbox, scaled by the cube of the size on
    /// another terrain).
    bool water_flowing = true;
    /// The flowing water carries sand: cuts channels and drops fans (LiveWaterSettings::erode).
    bool water_erode = false;
    /// Metres (0: off): edges under the water longer than this are split (LiveWaterSettings::
    /// detail), so the water on a coarse terrain gets the triangles it flows through.
    double water_detail = 0.0;
    double water_rain = 0.0;
    double water_evaporation = 0.0;
    bool water_open_west = false;
    bool water_open_east = false;
    bool water_open_south = false;
    bool water_open_north = false;
    double water_nozzle = 2e-5;  ///< m³/s: 0.02 L/s
    /// m: the Water tool's jet radius (Nozzle::radius): the water lands on the vertices
    /// within it.
    double water_jet = 0.01;
    /// The Rain tool's rate (mm/h) on its disc (the Size): a cloudburst, so that a held
    /// shower shows within seconds on the sandbox.
    double water_shower = 2000.0;
    double contrast = 0.5;  ///< strength of the height contrast curve, [0, 1]
    bool vsync = true;
    /// Metres: the size (larger domain side) of the terrain the lengths above are for. A
    /// terrain of another size rescales them (terrain_scale.hpp); 1 m is the default sandbox.
    double scene_size = 1.0;
    /// The File panel's recent files (recent_files.hpp): absolute paths, newest first.
    std::vector<std::string> recent_files;
    /// The folder the last file dialog picked a file in: the next one starts there.
    std::string last_folder;
    /// Which file dialog Open..., Save As..., Import... and Export... show: "auto" (the
    /// desktop's zenity or kdialog when one is on PATH, else the editor's own browser),
    /// "native" or "imgui". The environment variable SANDTIN_FILE_DIALOG overrides it.
    std::string file_dialog = "auto";

    friend bool operator==(const EditorSettings&, const EditorSettings&) = default;
};

/// How a setting's range follows the terrain (terrain_scale.hpp).
enum class Scaling { None, Length, Volume };

/// The range a numeric setting may take on the 1 m sandbox; a length's range scales with the
/// terrain's size and a volume's with its cube. One table for every place a value comes in:
/// the panels' sliders offer exactly this range and clamp typed values (Ctrl+click) to it,
/// scripts' "set" clamps to it, and load_settings() puts a value outside it back to its
/// default, so no value the tools or the physics would refuse reaches them.
struct SettingRange {
    double lo = 0.0;
    double hi = 0.0;
    Scaling scaling = Scaling::None;

    /// The factor lengths or volumes carry on a terrain of `size` metres.
    constexpr double factor(double size) const {
        return scaling == Scaling::Length   ? size
               : scaling == Scaling::Volume ? size * size * size
                                            : 1.0;
    }
    constexpr double lo_at(double size) const { return lo * factor(size); }
    constexpr double hi_at(double size) const { return hi * factor(size); }
    /// `value` within the range on a terrain of `size` metres (NaN goes to the low end).
    double clamp(double value, double size) const;
    bool contains(double value, double size) const {
        return value >= lo_at(size) && value <= hi_at(size);
    }
};

inline constexpr SettingRange kToolRadiusRange{0.005, 0.15, Scaling::Length};
/// A stamp presses at least half a millimetre (on the sandbox): at 0 or above the surface it
/// would do nothing, silently.
inline constexpr SettingRange kToolDepthRange{0.0005, 0.04, Scaling::Length};
inline constexpr SettingRange kStrokeSpacingRange{0.02, 2.0};  ///< of the tool's radius
inline constexpr SettingRange kToolAngleRange{-180.0, 180.0};  ///< degrees
inline constexpr SettingRange kBrushStrengthRange{0.0005, 0.02, Scaling::Length};
inline constexpr SettingRange kBrushBlendRange{0.05, 1.0};
inline constexpr SettingRange kPourVolumeRange{1e-6, 2e-4, Scaling::Volume};
inline constexpr SettingRange kErosionStepsRange{1.0, 200.0};
/// 0 removes only exactly planar patches (which moves no volume).
inline constexpr SettingRange kSimplifyToleranceRange{0.0, 0.005, Scaling::Length};
inline constexpr SettingRange kRelocationRadiusRange{0.001, 0.05, Scaling::Length};
inline constexpr SettingRange kSettleMarginRange{0.0, 0.1};
inline constexpr SettingRange kContrastRange{0.0, 1.0};
inline constexpr SettingRange kWaterRainRange{0.0, 500.0};         ///< mm/h
inline constexpr SettingRange kWaterEvaporationRange{0.0, 500.0};  ///< mm/h
/// m³/s: a trickle (1 mL/s) to a garden hose's flow (0.5 L/s) on the sandbox.
inline constexpr SettingRange kWaterNozzleRange{1e-6, 5e-4, Scaling::Volume};
/// m: the Water tool's jet, a point (0: the nearest vertex) to 5 cm across on the sandbox.
inline constexpr SettingRange kWaterJetRange{0.0, 0.05, Scaling::Length};
/// m: the water's detail, 0 (off) to 5 cm on the sandbox.
inline constexpr SettingRange kWaterDetailRange{0.0, 0.05, Scaling::Length};
/// mm/h: heavy rain (10) to a hose's spray (50 000) on the Rain tool's disc.
inline constexpr SettingRange kWaterShowerRange{10.0, 50000.0};

/// The range of stroke_spacing_ratio the panel offers and a settings file may hold.
inline constexpr double kMinStrokeSpacingRatio = kStrokeSpacingRange.lo;
inline constexpr double kMaxStrokeSpacingRatio = kStrokeSpacingRange.hi;

std::filesystem::path default_settings_path();
/// Missing file: defaults. Unreadable or invalid JSON: defaults, with `problem` set to why. A
/// field of the wrong type or outside its range (SettingRange, at the file's scene_size) falls
/// back to its default alone, and `problem` names it, its value and its range: the rest of the
/// file still counts, and the editor starts whatever a hand edit or an older version wrote.
/// The tool is found by its label; an index (files of older versions, whose palette had
/// another order) or a label the palette no longer has falls back to the first tool.
EditorSettings load_settings(const std::filesystem::path& path, std::string* problem = nullptr);
/// Written atomically; throws std::runtime_error naming the path on failure.
void save_settings(const std::filesystem::path& path, const EditorSettings& settings);

}  // namespace sandtin::editor
