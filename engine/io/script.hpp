#pragma once
// Sculpting scripts: `sandtin run script.json` applies a list of operations to a terrain.
//
//   { "version": 1,
//     "terrain": { "size": [1, 1], "points": 10000, "seed": 1, "height": 0 },
//     "settings": { "simplify_tolerance": 0.0005, "keep_generations": 64, "simplify": true,
//                   "relocation_radius": 0.01, "schedule": "sequential", "threads": 1 },
//     "operations": [
//       { "op": "stamp",  "tool": {...}, "at": [x, y], "angle": 0, "depth": 0.05 },
//       { "op": "stroke", "tool": {...}, "path": [[x, y], ...], "curve": false, "spacing": 0.01,
//                         "depth": 0.05, "follow_path": true },
//       { "op": "pour",   "at": [x, y], "volume": 1e-4, "radius": 0.02 },
//       { "op": "remove", "path": [[x, y], ...], "volume": 1e-4, "radius": 0.02, "spacing": 0.01 },
//       { "op": "brush",  "kind": "raise", "at": [x, y], "radius": 0.05, "strength": 0.002 },
//       { "op": "erode", "until_rest": true },
//       { "op": "simplify", "tolerance": 0.001 },
//       { "op": "save", "path": "checkpoint.sandtin" } ] }
//
// A bare array of operations is accepted too. All lengths are metres, angles radians, volumes
// m³. See README.md ("Scripts") for every field. Parsing checks the whole script before anything
// runs, so a bad script leaves the terrain untouched; errors name the line, the operation and
// the field.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/progress.hpp"
#include "io/script_water.hpp"
#include "io/script_weather.hpp"
#include "io/session_file.hpp"
#include "physics/sand_physics.hpp"
#include "physics/talus_solver.hpp"
#include "physics/terrain_solver.hpp"
#include "tin/tin.hpp"
#include "tools/brushes.hpp"
#include "tools/sand.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"

namespace sandtin {

struct StampOp {
    std::shared_ptr<const Tool> tool;
    Vec2 at;
    double angle = 0.0;
    DepthMode depth_mode = DepthMode::Relative;
    double depth = 0.0;  ///< metres below the terrain (relative) or the bottom height (absolute)
};

struct StrokeOp {
    std::shared_ptr<const Tool> tool;
    std::vector<Vec2> path;  ///< already densified when the script asked for a curve
    StrokeSettings settings;
    int erode_iterations = 0;  ///< relaxation iterations after each stamp ("erode": true)
};

struct PourOp {
    bool remove = false;
    std::vector<Vec2> points;  ///< one point, or the samples along a path
    double volume = 0.0;       ///< total m³ over all points
    PourSettings settings;
};

struct BrushOp {
    std::vector<Vec2> points;  ///< dab centres
    BrushSettings settings;
    /// Paint: the saturation painted, in [0, 1]; by default the material's default_moisture.
    std::optional<float> moisture;
};

/// Sand relaxation: a number of iterations, or until the sand is at rest.
struct ErodeOp {
    int iterations = 0;  ///< when until_rest is false
    bool until_rest = false;
    int max_iterations = 100000;            ///< cap when until_rest
    std::optional<TalusSettings> settings;  ///< overrides the script's physics settings
    /// First settle by projection onto the repose set (physics/settle_by_projection.hpp), then
    /// relax as asked.
    bool project = false;
    /// With project: rounds of vertices put on the rest surface's bends, the toe and the crest,
    /// each followed by a projection (physics/settle_fitted_to_kinks.hpp); 0: none.
    int fit_bends = 0;
};

struct SimplifyOp {
    std::optional<double> tolerance;
};

/// Writes the session as it stands (atomically) to `path`: a checkpoint in a long script.
struct SaveOp {
    std::filesystem::path path;  ///< resolved against the script's directory
};

/// Extension point for operations defined outside the sculpting tools (erosion, recorded
/// haptic sessions): a name and a callable that runs it and reports JSON.
struct CustomOp {
    std::string name;
    std::function<nlohmann::json(Tin&, SculptContext&)> run;
};

using ScriptOperation = std::variant<StampOp, StrokeOp, PourOp, BrushOp, ErodeOp, SimplifyOp,
                                     SaveOp, WaterOp, DryOp, WeatherOp, CustomOp>;

struct ScriptStep {
    ScriptOperation operation;
    std::string op_name;
    std::size_t line = 0;  ///< 1-based line of the operation in the script text
};

/// The terrain a script starts from when no input session is given ("terrain" field):
/// a W x H m rectangle with `points` random points (seeded) at `height`.
struct ScriptTerrain {
    Vec2 size{1.0, 1.0};
    std::size_t points = 0;
    std::uint64_t seed = 1;
    double height = 0.0;
    /// Metres of sand over a flat bedrock at height - sand_depth; none: no bedrock.
    std::optional<double> sand_depth;
};

/// Builds the terrain a "terrain" object describes.
Tin make_script_terrain(const ScriptTerrain& terrain, TinOptions options = {});

/// Most stamps or dabs one operation (or one haptic replay) may place along its path: a
/// million circle stamps take about five minutes; a spacing of 1e-7 m along a 1 m path would
/// ask for ten million, an hour or more, and is almost certainly a typo.
inline constexpr double kMaxPlacementsPerOperation = 1e6;

struct Script {
    /// The script's name as parsed (its path): runtime errors and warnings begin with
    /// "<name>:<line>:", as parse errors do. Empty: they begin with "line <line>:".
    std::string name;
    std::vector<ScriptStep> steps;
    TalusSettings physics;  ///< "settings": relocation_radius, schedule, damping, ...
    bool uses_physics = false;
    std::optional<ScriptTerrain> terrain;
    std::optional<double> simplify_tolerance;
    std::optional<Generation> keep_generations;
    std::optional<bool> simplify;
};

/// Parses operation kinds that other rooms add (e.g. "erode"). Returns nullopt for kinds it
/// does not know; throws JsonInputError for bad fields.
using ScriptExtension = std::function<std::optional<CustomOp>(
    const std::string& op, const nlohmann::json& object, const std::string& context)>;

/// Parses and validates a script. Throws JsonInputError with "<name>:<line>: operation <k>
/// (<op>): ..." messages.
Script parse_script(std::string_view text, const std::string& name,
                    const std::filesystem::path& base_dir,
                    const std::vector<ScriptExtension>& extensions = {});

/// Creates the relaxation a script's erosion runs on, following `tin` from now on, with the
/// script's settings and the scene's materials. Empty: the CPU reference (SandPhysics);
/// `sandtin run --physics gpu` supplies the GPU one (gpu/make_relaxation_solver.hpp).
using RelaxationSolverFactory = std::function<std::unique_ptr<RelaxationSolver>(
    Tin& tin, const TalusSettings& settings, const MaterialTable& materials)>;

/// Runs the steps of a script one at a time against a terrain, keeping the sand physics (which
/// follows every change to the TIN) alive between steps. run_script is a loop over it; the
/// stress runner feeds it generated steps.
class ScriptRunner {
  public:
    /// Applies the script's settings to the context. The physics is created now, so it sees
    /// every change, when the script uses it or `with_physics` is set.
    /// `make_solver` replaces the CPU physics when given. `carried`, when given, is the session the
    /// terrain came from: its material table (io/scene_materials.hpp) is the one the physics
    /// and the paint brush use (the presets otherwise), and `save` checkpoints carry its
    /// metadata (scene name, tool settings, import report) and its chunks from newer versions,
    /// as the final output does; its terrain is not used. Throws JsonInputError for a material
    /// table in its metadata that is not valid.
    ScriptRunner(const Script& script, Tin& tin, SculptContext& context, bool with_physics = false,
                 const RelaxationSolverFactory& make_solver = {}, const Session* carried = nullptr);
    ~ScriptRunner();
    ScriptRunner(const ScriptRunner&) = delete;
    ScriptRunner& operator=(const ScriptRunner&) = delete;

    /// Runs one step; returns its JSON report ("op", "line", "ms" and the op's own fields;
    /// "volume_change" is the m³ the step added to the terrain by its own account).
    /// `progress` (io/progress.hpp) hears the step's own fractions: a stroke's stamps, a
    /// pour's or a brush's points; other steps report nothing inside.
    nlohmann::json run(const ScriptStep& step, const ProgressCallback& progress = {});

    /// The relaxation, or null when the runner was created without physics.
    RelaxationSolver* solver() { return solver_.get(); }

  private:
    nlohmann::json run_op(const StampOp& op);
    nlohmann::json run_op(const StrokeOp& op);
    nlohmann::json run_op(const ErodeOp& op);
    nlohmann::json run_op(const PourOp& op);
    nlohmann::json run_op(const BrushOp& op);
    nlohmann::json run_op(const SimplifyOp& op);
    nlohmann::json run_op(const SaveOp& op);
    nlohmann::json run_op(const WaterOp& op);
    nlohmann::json run_op(const DryOp& op);
    nlohmann::json run_op(const WeatherOp& op);
    nlohmann::json run_op(const CustomOp& op);
    /// Tells the current step's progress that `done` of its `total` points are placed.
    void report_points_done(std::size_t done, std::size_t total) const;
    /// One call of the solver; the vertices it changed go to eroded_, its float drift (m³)
    /// to erosion_drift_.
    PhysicsStepReport relax(int iterations, bool until_rest);
    /// Relaxation, then the simplification of what it touched (and, until rest, the settling
    /// of what the simplification steepened).
    PhysicsStepReport erode(int iterations, bool until_rest);

    Tin& tin_;
    SculptContext& context_;
    Session carried_;  ///< metadata and unknown chunks only; the terrain stays empty
    MaterialTable materials_;
    std::unique_ptr<RelaxationSolver> solver_;
    std::vector<VertexId> eroded_;  ///< vertices the current step's relaxation changed
    double erosion_drift_ = 0.0;    ///< m³ the current step's float relaxation drifted
    const ProgressCallback* step_progress_ = nullptr;  ///< the current step's, while it runs
};

/// Applies the script's settings to the context and runs every step; returns one JSON report
/// per step; a step that did something the artist should hear of (extrusion that lost sand
/// over the terrain's edge) has a "warning" string naming its line and operation. `carried`,
/// when given, is the session the terrain came from (see ScriptRunner's constructor).
/// `progress` (io/progress.hpp) hears each step as "operation k of n (op)", its share of the
/// script 1/n, and what the step reports inside it (ScriptRunner::run).
nlohmann::json run_script(const Script& script, Tin& tin, SculptContext& context,
                          const RelaxationSolverFactory& make_solver = {},
                          const Session* carried = nullptr, const ProgressCallback& progress = {});

}  // namespace sandtin
