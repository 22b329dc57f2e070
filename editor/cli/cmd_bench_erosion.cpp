// sandtin bench erosion: run time to rest against error, TIN versus the regular-grid baseline
// (issue 4; the seeds' Fig. 8.4a compares the same two), each under both slope rules (issue 39:
// two discretisations of one continuum model), and CPU Jacobi throughput.
//
//   sandtin bench erosion [--json] [--quick] [--out DIR] [--throughput] [--settle-margin M]
//                         [--scenes cone,half-cone,quarter-cone,step,dunes]
//                         [--rules edge,face,projection] [--repeats N]
//                         [--no-throughput]
//   (--throughput: only the throughput tables, bench_erosion_throughput.hpp; --no-throughput:
//   without them; --scenes and --rules: a subset of the table; --repeats: runs per row, whose
//   median is kept, 3 by default and 1 with --quick)
//
// Methods: "tin" and "grid" run the edge rule under seeds_rule() (no settle margin); "tin-face"
// and "grid-face" run the face rule with the settle margin M (default: the physics', 0.03);
// "tin-proj" and "grid-proj" (--rules projection) settle by projection onto the repose set
// (physics/repose_projection.hpp), the face rule finishing. On the TIN a scout (the face rule
// at margin 0.25) first finds where the sand goes and refines it to r_S; the surface before any
// relaxation is then put back on that mesh and projected, with the rest surface's bends (the
// toe, the crest) fitted by one round of vertices on them and a second projection
// (physics/settle_fitted_to_kinks.hpp); the cone is poured all at once.
// Scenes, with their references:
//  - cone: V = 0.01 m³ poured at the centre of a flat 1 m square (dry sand, 32°). The TIN
//    starts from two triangles and refines through r_S; the grid pours into its centre cell.
//    Reference: the analytic cone. Also the mean inside 1.2 R and the toe in 32 directions.
//  - half-cone, quarter-cone: the same volume poured at the middle of a wall and into a corner
//    (the grid: into the cell there, its centre the apex). Reference: the half and the quarter
//    of the analytic cone of volume 2 V and 4 V (the walls hold the rest).
//  - step: a straight step of sand 0.1 m high across the square at 30° to the x axis, its top
//    at 0.2 m. Reference: the straight slope at tan(alpha) through the step's mid-height (cut
//    equals fill), judged inside the central 0.6 m square, away from the walls the step meets.
//    The TIN starts with the step's two edges resolved at r_S and refines through r_S.
//  - dunes: a sinusoidal field with slopes up to 2x the angle of repose over the whole square
//    (uniform detail). TINs of random points of several densities and grids of several
//    resolutions; reference: the finest grid of the same rule run to rest (which favours the
//    grid; said here and in the JSON).
// Error, sampled on a 200 x 200 lattice (of the judged region): mean |z - z_ref| (the mean
// absolute volume difference per unit area, Fig. 8.4a's metric) and max |z - z_ref|; each run
// also judges its rested surface face by face. Times are thread CPU time (other agents share
// this 2-core machine; wall time is also given), each the median of `repeats` runs. CSV and
// SVG plots go to DIR.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "bench_common.hpp"
#include "bench_erosion_run.hpp"
#include "bench_erosion_throughput.hpp"
#include "commands.hpp"
#include "physics/cone.hpp"
#include "physics/face_slopes.hpp"
#include "physics/grid_erosion.hpp"
#include "physics/sand_physics.hpp"
#include "physics/settle_by_projection.hpp"
#include "physics/settle_fitted_to_kinks.hpp"
#include "progress_line.hpp"
#include "tin/tin.hpp"

namespace sandtin::cli {

namespace {

using bench::CpuStopwatch;
using bench::Stopwatch;
using HeightAt = std::function<double(Vec2)>;

constexpr double kVolume = 0.01;
constexpr int kSamples = 200;
constexpr int kMaxIterations = 400000;

// ---- Scenes and their references ------------------------------------------------------------

double dunes(Vec2 p) {
    // Slope amplitude 0.05 * 2 pi * 4 = 1.26, twice tan(32°).
    return 0.2 + 0.05 * std::sin(2.0 * std::numbers::pi * 4.0 * p.x) *
                     std::sin(2.0 * std::numbers::pi * 3.0 * p.y + 0.5);
}

/// The step: its top (m), its foot, and the signed distance (m) of p from its line through
/// the square's centre at 30° to the x axis, positive on the low side.
constexpr double kStepTop = 0.2, kStepFoot = 0.1;
double step_distance(Vec2 p) {
    const double angle = std::numbers::pi / 6.0;
    return -(p.x - 0.5) * std::sin(angle) + (p.y - 0.5) * std::cos(angle);
}
Vec2 step_point(double along, double across) {
    const double angle = std::numbers::pi / 6.0;
    return {0.5 + along * std::cos(angle) - across * std::sin(angle),
            0.5 + along * std::sin(angle) + across * std::cos(angle)};
}
double step_initial(Vec2 p) {
    return step_distance(p) < 0.0 ? kStepTop : kStepFoot;
}
/// At rest: a straight slope at tan(alpha) through the mid-height, cut equals fill.
double step_rest(Vec2 p) {
    const double mid = 0.5 * (kStepTop + kStepFoot);
    return std::clamp(mid - step_distance(p) * dry_sand_tan_alpha(), kStepFoot, kStepTop);
}
const Rect kStepJudged{{0.2, 0.2}, {0.8, 0.8}};

// ---- Measures --------------------------------------------------------------------------------

/// A disc of the plane (m): where a cone's pile error is judged.
struct Disc {
    Vec2 centre;
    double radius = 0.0;
};

/// Mean and max |z - reference| on the lattice over `region`; with `pile`, also the mean over
/// the lattice points inside it (row.pile_error), from the same samples.
void measure_error(ErosionRun& row, const HeightAt& z, const HeightAt& reference,
                   Rect region = Rect::from_size(1.0, 1.0), std::optional<Disc> pile = {}) {
    double sum = 0.0, worst = 0.0, pile_sum = 0.0;
    int pile_count = 0;
    for (int j = 0; j < kSamples; ++j) {
        for (int i = 0; i < kSamples; ++i) {
            const Vec2 p{region.min.x + (i + 0.5) / kSamples * region.width(),
                         region.min.y + (j + 0.5) / kSamples * region.height()};
            const double d = std::abs(z(p) - reference(p));
            sum += d;
            worst = std::max(worst, d);
            if (pile && distance(p, pile->centre) <= pile->radius) {
                pile_sum += d;
                ++pile_count;
            }
        }
    }
    row.mean_error = sum / (kSamples * kSamples);
    row.max_error = worst;
    if (pile) row.pile_error = pile_count > 0 ? pile_sum / pile_count : 0.0;
}

void take_faces(ErosionRun& row, const FaceSlopeReport& r) {
    row.steep_share = r.steep_share_of_slopes();
    row.max_face_ratio = r.max_ratio;
    row.skipped_faces = static_cast<long>(r.skipped_faces);
}

FaceSlopeOptions judged_in(std::optional<Rect> region) {
    FaceSlopeOptions options;
    options.region = region;
    return options;
}

/// Runs `run` `repeats` times and keeps the row with the median CPU time.
ErosionRun median_of(int repeats, const std::function<ErosionRun()>& run) {
    std::vector<ErosionRun> rows;
    for (int r = 0; r < repeats; ++r)
        rows.push_back(run());
    std::sort(rows.begin(), rows.end(),
              [](const ErosionRun& a, const ErosionRun& b) { return a.cpu_ms < b.cpu_ms; });
    return rows[rows.size() / 2];
}

// ---- Methods ---------------------------------------------------------------------------------

/// The edge rule runs under seeds_rule() on both discretisations, as the seeds did; the face
/// rule with `face_margin`.
TalusSettings rule_settings(SlopeRule rule, double face_margin) {
    TalusSettings settings = rule == SlopeRule::Edge ? seeds_rule() : TalusSettings{};
    settings.parameters.rule = rule;
    if (rule == SlopeRule::Face) settings.parameters.settle_margin = face_margin;
    return settings;
}

struct Method {
    SlopeRule rule = SlopeRule::Face;
    double face_margin = TalusParameters{}.settle_margin;
    /// Settled by projection onto the repose set (physics/repose_projection.hpp), the face
    /// rule (`rule` is Face) finishing what the projection's tolerance leaves.
    bool projection = false;
    /// The relaxation's settings (after a projection, settle_by_projection.hpp's margin).
    TalusSettings settings() const {
        return rule_settings(rule, projection ? kSettleMarginAfterProjection : face_margin);
    }
};

std::string method_name(bool grid, const Method& m) {
    if (m.projection) return grid ? "grid-proj" : "tin-proj";
    return std::string(grid ? "grid" : "tin") + (m.rule == SlopeRule::Face ? "-face" : "");
}

/// The scout's settle margin: before a projection, the face rule levelling towards 0.75 tan
/// alpha finds where the sand goes (a little farther than it will rest) and refines it to r_S,
/// in far fewer iterations than at the method's own margin.
constexpr double kScoutMargin = 0.25;

/// A projected TIN run: the scout relaxes and refines, `restore` puts back the surface before
/// any relaxation on the refined mesh, the projection settles it (one round fitting its bends)
/// and the face rule finishes.
PhysicsStepReport project_then_finish(Tin& tin, SandPhysics& physics, const Method& m,
                                      const std::function<void()>& restore) {
    physics.settings().parameters.settle_margin = kScoutMargin;
    PhysicsStepReport r = physics.run_to_rest(kMaxIterations);
    restore();
    settle_fitted_to_kinks(tin, MaterialTable::presets());
    physics.settings().parameters.settle_margin = m.settings().parameters.settle_margin;
    physics.activate_all();
    r.accumulate(physics.run_to_rest(kMaxIterations));
    return r;
}

/// The toe along the 32 directions from the apex that enter the domain: where the surface
/// first comes down to 1e-3 of the cone's height (bisected to 1e-4 R), against the analytic
/// toe at that level, R (1 - 1e-3). `worst` is the largest |toe radius / R - 1| (issue 39's
/// ±1.5 %), `bias` the mean of toe radius / R - 1.
struct ToeFigures {
    double worst = 0.0;
    double bias = 0.0;
};

ToeFigures measure_toe(const HeightAt& z, Vec2 apex, const Cone& cone, Rect domain) {
    ToeFigures toe;
    const double floor = 1e-3 * cone.height;
    int directions = 0;
    double sum = 0.0;
    for (int k = 0; k < 32; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / 32.0;
        const Vec2 dir{std::cos(angle), std::sin(angle)};
        if (!domain.contains(apex + dir * (1e-3 * cone.radius))) continue;  // into a wall
        double lo = 0.0, hi = 1.6 * cone.radius;  // z(lo) above the floor, z(hi) below
        while (hi - lo > 1e-4 * cone.radius) {
            const double mid = 0.5 * (lo + hi);
            (z(apex + dir * mid) > floor ? lo : hi) = mid;
        }
        const double offset = 0.5 * (lo + hi) / (cone.radius * (1.0 - 1e-3)) - 1.0;
        toe.worst = std::max(toe.worst, std::abs(offset));
        sum += offset;
        ++directions;
    }
    toe.bias = directions > 0 ? sum / directions : 0.0;
    return toe;
}

/// Fills the cost and face figures of a TIN run.
void finish_tin(ErosionRun& row, const Tin& tin, const PhysicsStepReport& r,
                const CpuStopwatch& cpu, const Stopwatch& wall,
                std::optional<Rect> judged = std::nullopt) {
    row.cpu_ms = cpu.ms();
    row.wall_ms = wall.ms();
    row.iterations = r.iterations;
    row.at_rest = r.at_rest;
    row.vertices = tin.vertex_count();
    take_faces(row, measure_face_slopes(tin, MaterialTable::presets(), judged_in(judged)));
}

/// A cone scene: V poured at the centre, at a wall's midpoint or into a corner, where the walls
/// keep 1, 1/2 or 1/4 of the analytic cone of volume V / share (issue 39's half and quarter
/// cones).
struct ConeScene {
    const char* name;
    Vec2 apex;
    double share;
    Cone cone() const { return Cone::from_volume(kVolume / share, dry_sand_tan_alpha()); }
};
constexpr ConeScene kCones[] = {
    {"cone", {0.5, 0.5}, 1.0}, {"half-cone", {0.0, 0.5}, 0.5}, {"quarter-cone", {0.0, 0.0}, 0.25}};

const ConeScene* cone_scene(const std::string& name) {
    for (const ConeScene& c : kCones) {
        if (name == c.name) return &c;
    }
    return nullptr;
}

/// The cone's error figures against the analytic cone centred at `apex`: the mean and max over
/// the square, the mean inside 1.2 R (the pile, issue 39's figure) and the toe, along the
/// directions that enter `domain` (the grid's is its centres' rectangle).
void judge_cone(ErosionRun& row, const HeightAt& z, Vec2 apex, const Cone& cone,
                Rect domain = Rect::from_size(1.0, 1.0)) {
    const HeightAt reference = [&](Vec2 p) { return cone.surface(distance(p, apex)); };
    measure_error(row, z, reference, Rect::from_size(1.0, 1.0), Disc{apex, 1.2 * cone.radius});
    row.pile_height = cone.height;
    const ToeFigures toe = measure_toe(z, apex, cone, domain);
    row.toe_error = toe.worst;
    row.toe_bias = toe.bias;
}

ErosionRun tin_cone(const ConeScene& scene, double rs, Method method) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.0, TinOptions{false});
    TalusSettings settings = method.settings();
    settings.parameters.relocation_radius = rs;
    ErosionRun row{scene.name, method_name(false, method), "r_S=" + std::to_string(rs)};
    row.spacing = rs;
    row.settle_margin = settings.parameters.settle_margin;
    CpuStopwatch cpu;
    Stopwatch wall;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    const VertexId apex = tin.insert_point(scene.apex, 0.0);  // the corner's own vertex there
    const VertexId one[] = {apex};
    physics.refine_around(one);
    PhysicsStepReport r;
    const auto pour_all = [&] {
        for (VertexId v : tin.vertices_in_disc({0.5, 0.5}, 1.0))
            tin.set_height(v, v == apex ? kVolume / tin.vertices().lumped_area[apex.value] : 0.0);
    };
    if (method.projection) {
        // All at once: the projection is the collapse's exact rest state.
        pour_all();
        r = project_then_finish(tin, physics, method, pour_all);
    } else {
        // Poured in 100 portions at one vertex, as from a nozzle (see tests/physics/cone_test).
        for (int k = 0; k < 100; ++k) {
            tin.set_height(
                apex, tin.height(apex) + kVolume / 100 / tin.vertices().lumped_area[apex.value]);
            r.accumulate(physics.step(50));
        }
        r.accumulate(physics.run_to_rest(kMaxIterations));
    }
    finish_tin(row, tin, r, cpu, wall);
    LocateHint hint;
    judge_cone(
        row, [&](Vec2 p) { return *tin.height_at(p, &hint); }, scene.apex, scene.cone());
    return row;
}

/// The step on a TIN: the square's corners and the step's two edges, r_S apart along them and
/// r_S apart across (so that no triangle spans both: the initial surface is the step itself).
ErosionRun tin_step(double rs, Method method) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), kStepFoot, TinOptions{false});
    for (VertexId v : tin.vertices_in_disc({0.5, 0.5}, 1.0))  // the four corners
        tin.set_height(v, step_initial(tin.position(v)));
    const Rect square = Rect::from_size(1.0, 1.0);
    for (const double across : {-0.5 * rs, 0.5 * rs}) {
        for (double along = -1.2; along <= 1.2; along += rs) {
            const Vec2 p = step_point(along, across);
            if (square.contains(p)) tin.insert_point(p, across < 0.0 ? kStepTop : kStepFoot);
        }
    }
    TalusSettings settings = method.settings();
    settings.parameters.relocation_radius = rs;
    ErosionRun row{"step", method_name(false, method), "r_S=" + std::to_string(rs)};
    row.spacing = rs;
    row.settle_margin = settings.parameters.settle_margin;
    CpuStopwatch cpu;
    Stopwatch wall;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    physics.activate_all();
    const auto restore_step = [&] {
        for (VertexId v : tin.vertices_in_disc({0.5, 0.5}, 1.0))
            tin.set_height(v, step_initial(tin.position(v)));
    };
    const PhysicsStepReport r = method.projection
                                    ? project_then_finish(tin, physics, method, restore_step)
                                    : physics.run_to_rest(kMaxIterations);
    finish_tin(row, tin, r, cpu, wall, kStepJudged);
    LocateHint hint;
    measure_error(
        row, [&](Vec2 p) { return *tin.height_at(p, &hint); }, step_rest, kStepJudged);
    return row;
}

ErosionRun tin_dunes(std::size_t points, const HeightAt& reference, Method method) {
    ErosionRun row{"dunes", method_name(false, method), std::to_string(points) + " points"};
    row.spacing = std::sqrt(1.0 / static_cast<double>(points));
    row.settle_margin = method.settings().parameters.settle_margin;
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), points, 21, dunes, TinOptions{false});
    CpuStopwatch cpu;
    Stopwatch wall;
    SandPhysics physics(tin, MaterialTable::presets(), method.settings());
    // Uniform detail from the start: no scout, the projection settles the dunes as they are.
    if (method.projection) settle_fitted_to_kinks(tin, MaterialTable::presets());
    physics.activate_all();
    const PhysicsStepReport r = physics.run_to_rest(kMaxIterations);
    finish_tin(row, tin, r, cpu, wall);
    LocateHint hint;
    measure_error(
        row, [&](Vec2 p) { return *tin.height_at(p, &hint); }, reference);
    return row;
}

struct GridRun {
    ErosionRun row;
    std::unique_ptr<GridErosion> grid;
};

/// A grid run: `shape` sets the initial heights (and pours), then relaxation to rest.
GridRun grid_run(const std::string& scene, int n, Method method,
                 const std::function<void(GridErosion&)>& shape) {
    GridRun g{{scene, method_name(true, method), std::to_string(n) + "x" + std::to_string(n)},
              nullptr};
    g.row.spacing = 1.0 / n;
    g.row.settle_margin = method.settings().parameters.settle_margin;
    CpuStopwatch cpu;
    Stopwatch wall;
    g.grid = std::make_unique<GridErosion>(Rect::from_size(1.0, 1.0), n, n, dry_sand_tan_alpha(),
                                           method.settings());
    shape(*g.grid);
    if (method.projection) g.grid->settle_by_projection();
    g.row.iterations = g.grid->run_to_rest(kMaxIterations);
    g.row.cpu_ms = cpu.ms();
    g.row.wall_ms = wall.ms();
    g.row.at_rest = g.grid->active_count() == 0;
    g.row.vertices = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    return g;
}

void grid_faces(GridRun& g, std::optional<Rect> judged = std::nullopt) {
    const std::vector<SlopeFace> faces = g.grid->faces();
    take_faces(g.row, measure_face_slopes(faces, judged_in(judged)));
}

ErosionRun grid_cone(const ConeScene& scene, int n, Method method) {
    GridRun g =
        grid_run(scene.name, n, method, [&](GridErosion& grid) { grid.pour(scene.apex, kVolume); });
    grid_faces(g);
    // The poured cell's centre is the apex (on a wall, the grid's own boundary runs through
    // it: the centres' rectangle is its domain); compare against the cone centred there.
    const auto cell = [n](double x) { return std::clamp(static_cast<int>(x * n), 0, n - 1); };
    const Vec2 apex = g.grid->centre(cell(scene.apex.x), cell(scene.apex.y));
    const Rect centres{g.grid->centre(0, 0), g.grid->centre(n - 1, n - 1)};
    judge_cone(
        g.row, [&](Vec2 p) { return g.grid->height_at(p); }, apex, scene.cone(), centres);
    return g.row;
}

void set_heights(GridErosion& grid, double (*height)(Vec2)) {
    for (int j = 0; j < grid.cells_y(); ++j) {
        for (int i = 0; i < grid.cells_x(); ++i)
            grid.height(i, j) = height(grid.centre(i, j));
    }
    grid.activate_all();
}

ErosionRun grid_step(int n, Method method) {
    GridRun g =
        grid_run("step", n, method, [](GridErosion& grid) { set_heights(grid, step_initial); });
    grid_faces(g, kStepJudged);
    measure_error(
        g.row, [&](Vec2 p) { return g.grid->height_at(p); }, step_rest, kStepJudged);
    return g.row;
}

GridRun grid_dunes(int n, Method method) {
    return grid_run("dunes", n, method, [](GridErosion& grid) { set_heights(grid, dunes); });
}

/// The comma-separated names given with `option`, each one of `all`; all of them without it.
std::vector<std::string> chosen(const Arguments& args, const std::string& option,
                                const std::vector<std::string>& all) {
    if (!args.has(option)) return all;
    std::vector<std::string> out;
    std::stringstream list(args.text(option));
    std::string name;
    while (std::getline(list, name, ',')) {
        if (std::find(all.begin(), all.end(), name) == all.end()) {
            std::string names;
            for (const std::string& a : all)
                names += (names.empty() ? "" : ", ") + a;
            throw std::invalid_argument(option + ": '" + name + "' is not one of " + names);
        }
        out.push_back(name);
    }
    if (out.empty()) throw std::invalid_argument(option + " names nothing");
    return out;
}

// ---- The table and its summaries -------------------------------------------------------------

struct Levels {
    std::vector<double> rs;            ///< TIN cones and step: r_S (m)
    std::vector<double> rs_projected;  ///< the same for the projection: one halving more
    std::vector<int> grid_n;           ///< grid cone and step: cells per side
    std::vector<std::size_t> points;   ///< TIN dunes
    std::vector<int> dune_n;           ///< grid dunes
    int dune_reference_n = 256;
};

Levels levels(bool quick) {
    if (quick) return {{0.04}, {0.04}, {32}, {1000}, {16}, 64};
    // The projection is cheap enough for three halvings of r_S (issue 39's convergence
    // figure); the local rules take minutes at r_S = 0.005.
    return {{0.04, 0.02, 0.01}, {0.04, 0.02, 0.01, 0.005},
            {32, 64, 128, 256}, {2000, 8000, 32000},
            {32, 64, 128},      256};
}

/// For one scene: the TIN run (of `tin_method`) that reaches the best error of the grid runs
/// (of `grid_method`) at the least CPU time, and how it compares (issue 39's target: <= 1/5 of
/// the grid's time with <= 1/10 of its vertices).
nlohmann::json time_to_error(const std::vector<ErosionRun>& rows, const std::string& scene,
                             const std::string& tin_method, const std::string& grid_method) {
    const ErosionRun* best_grid = nullptr;
    for (const ErosionRun& r : rows) {
        if (r.scene == scene && r.method == grid_method &&
            (best_grid == nullptr || r.mean_error < best_grid->mean_error))
            best_grid = &r;
    }
    const ErosionRun* tin_match = nullptr;
    for (const ErosionRun& r : rows) {
        if (r.scene == scene && r.method == tin_method && best_grid != nullptr &&
            r.mean_error <= best_grid->mean_error &&
            (tin_match == nullptr || r.cpu_ms < tin_match->cpu_ms))
            tin_match = &r;
    }
    nlohmann::json target = {{"scene", scene},
                             {"tin_method", tin_method},
                             {"grid_method", grid_method},
                             {"grid_best", best_grid ? to_json(*best_grid) : nlohmann::json()}};
    if (tin_match != nullptr && best_grid != nullptr) {
        target["tin_match"] = to_json(*tin_match);
        target["time_ratio"] = tin_match->cpu_ms / best_grid->cpu_ms;
        target["vertex_ratio"] =
            static_cast<double>(tin_match->vertices) / static_cast<double>(best_grid->vertices);
        target["met"] = tin_match->cpu_ms <= best_grid->cpu_ms / 5.0 &&
                        tin_match->vertices * 10 <= best_grid->vertices;
    } else {
        target["tin_match"] = nullptr;
        target["met"] = false;
    }
    return target;
}

/// What the command line asked for.
struct BenchOptions {
    bool quick = false;
    double face_margin = TalusParameters{}.settle_margin;
    std::vector<std::string> scenes, rules;
    bool throughput = true;  ///< with the throughput tables
    bool throughput_only = false;
    int repeats = 3;
    std::optional<std::filesystem::path> out;

    bool wants(const char* scene) const {
        return std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
    }
};

BenchOptions parse_options(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--quick", 0},
                               {"--json", 0},
                               {"--out", 1},
                               {"--throughput", 0},
                               {"--settle-margin", 1},
                               {"--scenes", 1},
                               {"--rules", 1},
                               {"--repeats", 1},
                               {"--no-throughput", 0}});
    args.require_positionals(1,
                             "sandtin bench erosion [--quick] [--json] [--out DIR] "
                             "[--throughput] [--settle-margin M] "
                             "[--scenes cone,half-cone,quarter-cone,step,dunes] "
                             "[--rules edge,face,projection] [--repeats N] [--no-throughput]");
    BenchOptions o;
    o.quick = args.has("--quick");
    o.scenes = chosen(args, "--scenes", {"cone", "half-cone", "quarter-cone", "step", "dunes"});
    o.rules = chosen(args, "--rules", {"edge", "face", "projection"});
    o.throughput = !args.has("--no-throughput");
    o.throughput_only = args.has("--throughput");
    o.repeats = o.quick ? 1 : 3;
    if (args.has("--repeats")) {
        const double r = args.number("--repeats");
        if (!(r >= 1.0 && r <= 99.0) || r != std::floor(r))
            throw std::invalid_argument("--repeats must be a whole number from 1 to 99");
        o.repeats = static_cast<int>(r);
    }
    if (args.has("--settle-margin")) {
        o.face_margin = args.number("--settle-margin");
        if (!(o.face_margin >= 0.0 && o.face_margin <= kMaxSettleMargin))
            throw std::invalid_argument("--settle-margin must be in [0, " +
                                        std::to_string(kMaxSettleMargin) + "]");
    }
    if (args.has("--out")) o.out = args.text("--out");
    return o;
}

/// Counts the sections of the run and reports each as it starts.
class Sections {
  public:
    Sections(ProgressLine& progress, std::size_t total) : progress_(progress), total_(total) {}
    void start(const std::string& scene, const std::string& method, const std::string& level) {
        progress_.report({static_cast<double>(done_++) / static_cast<double>(total_),
                          scene + " (" + method + "), " + level});
    }

  private:
    ProgressLine& progress_;
    std::size_t total_;
    std::size_t done_ = 0;
};

/// The scenes run at levels of r_S (TIN) and cells (grid): the cones and the step.
constexpr const char* kPileScenes[] = {"cone", "half-cone", "quarter-cone", "step"};

/// The cones and the step: each method at each level, TIN then grid.
void run_piles(const BenchOptions& o, const Levels& lv, const std::vector<Method>& methods,
               Sections& sections, std::vector<ErosionRun>& rows) {
    for (const Method& m : methods) {
        for (const char* scene : kPileScenes) {
            if (!o.wants(scene)) continue;
            const ConeScene* cone = cone_scene(scene);
            for (double rs : m.projection ? lv.rs_projected : lv.rs) {
                std::ostringstream level;
                level << "r_S " << rs << " m";
                sections.start(scene, method_name(false, m), level.str());
                rows.push_back(median_of(
                    o.repeats, [&] { return cone ? tin_cone(*cone, rs, m) : tin_step(rs, m); }));
            }
            for (int n : lv.grid_n) {
                sections.start(scene, method_name(true, m), std::to_string(n) + "² grid");
                rows.push_back(median_of(
                    o.repeats, [&] { return cone ? grid_cone(*cone, n, m) : grid_step(n, m); }));
            }
        }
    }
}

/// The dunes, each rule against its own finest grid; returns the references' figures.
nlohmann::json run_dunes(const BenchOptions& o, const Levels& lv,
                         const std::vector<Method>& methods, Sections& sections,
                         std::vector<ErosionRun>& rows) {
    nlohmann::json references = nlohmann::json::array();
    for (const Method& m : methods) {
        sections.start("dunes", method_name(true, m),
                       std::to_string(lv.dune_reference_n) + "² reference");
        GridRun ref = grid_dunes(lv.dune_reference_n, m);
        references.push_back({{"method", ref.row.method},
                              {"grid", lv.dune_reference_n},
                              {"cpu_ms", ref.row.cpu_ms},
                              {"at_rest", ref.row.at_rest}});
        const GridErosion& ref_grid = *ref.grid;
        const HeightAt reference = [&](Vec2 p) { return ref_grid.height_at(p); };
        for (std::size_t pts : lv.points) {
            sections.start("dunes", method_name(false, m), std::to_string(pts) + " points");
            rows.push_back(median_of(o.repeats, [&] { return tin_dunes(pts, reference, m); }));
        }
        for (int n : lv.dune_n) {
            sections.start("dunes", method_name(true, m), std::to_string(n) + "² grid");
            rows.push_back(median_of(o.repeats, [&] {
                GridRun g = grid_dunes(n, m);
                grid_faces(g);
                measure_error(
                    g.row, [&](Vec2 p) { return g.grid->height_at(p); }, reference);
                return g.row;
            }));
        }
    }
    return references;
}

/// The runs, and per scene the fitted orders and the time to the grid's best error.
nlohmann::json summary(const std::vector<ErosionRun>& rows) {
    nlohmann::json j;
    nlohmann::json list = nlohmann::json::array();
    for (const ErosionRun& r : rows)
        list.push_back(to_json(r));
    j["runs"] = list;
    nlohmann::json orders = nlohmann::json::object();
    nlohmann::json targets = nlohmann::json::array();
    for (const char* scene : {"cone", "half-cone", "quarter-cone", "step", "dunes"}) {
        for (const char* method : {"tin", "tin-face", "tin-proj", "grid", "grid-face", "grid-proj"})
            orders[scene][method] = fitted_order(rows, scene, method);
        targets.push_back(time_to_error(rows, scene, "tin-proj", "grid-proj"));
        targets.push_back(time_to_error(rows, scene, "tin-proj", "grid-face"));
        targets.push_back(time_to_error(rows, scene, "tin-face", "grid-face"));
        targets.push_back(time_to_error(rows, scene, "tin", "grid"));
    }
    j["convergence_order"] = orders;
    j["time_to_error"] = targets;
    return j;
}

}  // namespace

int run_bench_erosion(const std::vector<std::string>& raw) {
    const BenchOptions o = parse_options(raw);
    ProgressLine progress("bench erosion");
    nlohmann::json j;
    j["bench"] = "erosion";
    if (o.throughput_only) {
        // Only the Jacobi throughput (issue 4's 10⁶-vertex figure), 5 runs per row.
        Sections sections(progress, 2);
        sections.start("throughput", "Jacobi", "solver alone");
        j["jacobi_throughput"] = jacobi_throughputs(o.quick, 5);
        sections.start("throughput", "Jacobi", "sand physics");
        j["sand_physics_throughput"] = sand_physics_throughputs(o.quick, 5);
        progress.finish();
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    const Levels lv = levels(o.quick);
    std::vector<Method> methods;
    for (const std::string& name : o.rules)
        methods.push_back({name == "edge" ? SlopeRule::Edge : SlopeRule::Face, o.face_margin,
                           name == "projection"});
    std::size_t piles = 0;
    for (const char* scene : kPileScenes)
        piles += o.wants(scene) ? 1 : 0;
    std::size_t total = o.throughput ? 2 : 0;
    for (const Method& m : methods) {
        total += piles * ((m.projection ? lv.rs_projected : lv.rs).size() + lv.grid_n.size()) +
                 (o.wants("dunes") ? 1 + lv.points.size() + lv.dune_n.size() : 0);
    }
    Sections sections(progress, total);
    std::vector<ErosionRun> rows;
    run_piles(o, lv, methods, sections, rows);
    const nlohmann::json dune_references =
        o.wants("dunes") ? run_dunes(o, lv, methods, sections, rows) : nlohmann::json::array();

    j.update(summary(rows));
    j["repeats"] = o.repeats;
    j["timer"] = "thread CPU time, median of repeats; wall time alongside";
    j["face_settle_margin"] = o.face_margin;
    j["dunes_reference"] = {
        {"what", "each rule's finest grid run to rest (a grid reference favours the grid)"},
        {"runs", dune_references}};
    if (o.throughput) {
        sections.start("throughput", "Jacobi", "solver alone");
        j["jacobi_throughput"] = jacobi_throughputs(o.quick, 3);
        sections.start("throughput", "Jacobi", "sand physics");
        j["sand_physics_throughput"] = sand_physics_throughputs(o.quick, 3);
    }
    progress.finish();
    if (o.out) {
        std::filesystem::create_directories(*o.out);
        write_erosion_csv(*o.out / "erosion.csv", rows);
        write_erosion_svg(*o.out / "erosion.svg", rows);
        j["csv"] = (*o.out / "erosion.csv").string();
        j["svg"] = (*o.out / "erosion.svg").string();
    }
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
