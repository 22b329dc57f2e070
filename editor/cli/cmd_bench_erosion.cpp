// sandtin bench erosion: run time to rest against error, TIN versus the regular-grid baseline
// (issue 4; the seeds' Fig. 8.4a compares the same two), and CPU Jacobi throughput.
//
//   sandtin bench erosion [--json] [--quick] [--out DIR] [--throughput]
//   (--throughput: only the CPU Jacobi throughput on about 10⁶ vertices, 1 and 2 threads, of
//   the solver on three numberings of one graph and of SandPhysics in TIN and strip order)
//
// Scenes:
//  - cone: V = 0.01 m³ poured at the centre of a flat 1 m square (dry sand, 32°). The TIN
//    starts from two triangles and refines through r_S; the grid pours into its centre cell.
//    Reference: the analytic cone.
//  - dunes: a sinusoidal field with slopes up to 2x the angle of repose over the whole square
//    (uniform detail). TINs of random points of several densities and grids of several
//    resolutions; reference: the 256 x 256 grid run to rest.
// Error, sampled on a 200 x 200 lattice: mean |z - z_ref| (the mean absolute volume
// difference per unit area, Fig. 8.4a's metric) and max |z - z_ref|. Times are thread CPU
// time (other agents share this 2-core machine; wall time is also given), each the median of
// `repeats` runs. CSV and an SVG plot go to DIR.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "bench_common.hpp"
#include "commands.hpp"
#include "physics/cone.hpp"
#include "physics/face_slopes.hpp"
#include "physics/grid_erosion.hpp"
#include "physics/sand_physics.hpp"
#include "physics/talus_kernel_avx512.hpp"
#include "progress_line.hpp"
#include "tin/tin.hpp"
#include "util/process_cpu_time.hpp"

namespace sandtin::cli {

namespace {

using bench::CpuStopwatch;
using bench::Stopwatch;
using HeightAt = std::function<double(Vec2)>;

constexpr double kVolume = 0.01;
constexpr int kSamples = 200;

struct Row {
    std::string scene, method, level;
    std::size_t vertices = 0;
    long iterations = 0;
    double cpu_ms = 0.0, wall_ms = 0.0;
    double mean_error = 0.0, max_error = 0.0;
    bool at_rest = false;
    double settle_margin = 0.0;  ///< the relaxation's (0 for the grid)
    /// Per face (physics/face_slopes.hpp), TIN rows only: the share of the slopes' area
    /// steeper than tan(alpha) (1 + 1e-3), the steepest face's |∇h| / tan(alpha), and the
    /// slivers skipped. Negative on grid rows.
    double steep_share = -1.0, max_face_ratio = -1.0;
    long skipped_faces = -1;
};

void measure_faces(Row& row, const Tin& tin) {
    const FaceSlopeReport r = measure_face_slopes(tin, MaterialTable::presets());
    row.steep_share = r.steep_share_of_slopes();
    row.max_face_ratio = r.max_ratio;
    row.skipped_faces = static_cast<long>(r.skipped_faces);
}

void measure_error(Row& row, const HeightAt& z, const HeightAt& reference) {
    double sum = 0.0, worst = 0.0;
    for (int j = 0; j < kSamples; ++j) {
        for (int i = 0; i < kSamples; ++i) {
            const Vec2 p{(i + 0.5) / kSamples, (j + 0.5) / kSamples};
            const double d = std::abs(z(p) - reference(p));
            sum += d;
            worst = std::max(worst, d);
        }
    }
    row.mean_error = sum / (kSamples * kSamples);
    row.max_error = worst;
}

double dunes(Vec2 p) {
    // Slope amplitude 0.05 * 2 pi * 4 = 1.26, twice tan(32°).
    return 0.2 + 0.05 * std::sin(2.0 * std::numbers::pi * 4.0 * p.x) *
                     std::sin(2.0 * std::numbers::pi * 3.0 * p.y + 0.5);
}

double tan_alpha() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

/// Runs `run` `repeats` times and keeps the row with the median CPU time.
Row median_of(int repeats, const std::function<Row()>& run) {
    std::vector<Row> rows;
    for (int r = 0; r < repeats; ++r)
        rows.push_back(run());
    std::sort(rows.begin(), rows.end(),
              [](const Row& a, const Row& b) { return a.cpu_ms < b.cpu_ms; });
    return rows[rows.size() / 2];
}

/// The TIN's method name under a slope rule: "tin" (edges) or "tin-face" (faces).
std::string tin_method(SlopeRule rule) {
    return rule == SlopeRule::Face ? "tin-face" : "tin";
}

/// The edge rule runs under seeds_rule(), as the grid baseline does, so that the comparison is
/// between two discretisations of one rule. The face rule runs with the physics' default settle
/// margin: without one it creeps for ever on the dunes (tiny trades near the threshold, the
/// face bound being non-monotone where a descent line leaves its face), while its surface has
/// long met the face criterion; with it the dunes rest in about a hundred iterations.
TalusSettings rule_settings(SlopeRule rule) {
    TalusSettings settings = rule == SlopeRule::Edge ? seeds_rule() : TalusSettings{};
    settings.parameters.rule = rule;
    return settings;
}

Row tin_cone(double rs, SlopeRule rule) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.0, TinOptions{false});
    TalusSettings settings = rule_settings(rule);
    settings.parameters.relocation_radius = rs;
    Row row{"cone", tin_method(rule), "r_S=" + std::to_string(rs)};
    row.settle_margin = settings.parameters.settle_margin;
    CpuStopwatch cpu;
    Stopwatch wall;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    // Poured in 100 portions at one vertex, as from a nozzle (see tests/physics/cone_test).
    const VertexId apex = tin.insert_point_on_surface({0.5, 0.5});
    const VertexId one[] = {apex};
    physics.refine_around(one);
    PhysicsStepReport r;
    for (int k = 0; k < 100; ++k) {
        tin.set_height(apex,
                       tin.height(apex) + kVolume / 100 / tin.vertices().lumped_area[apex.value]);
        r.accumulate(physics.step(50));
    }
    r.accumulate(physics.run_to_rest(400000));
    row.cpu_ms = cpu.ms();
    row.wall_ms = wall.ms();
    row.iterations = r.iterations;
    row.at_rest = r.at_rest;
    row.vertices = tin.vertex_count();
    measure_faces(row, tin);
    const Cone cone = Cone::from_volume(kVolume, tan_alpha());
    LocateHint hint;
    measure_error(
        row, [&](Vec2 p) { return *tin.height_at(p, &hint); },
        [&](Vec2 p) {
            return cone.surface(distance(p, {0.5, 0.5}));
        });
    return row;
}

Row grid_cone(int n) {
    Row row{"cone", "grid", std::to_string(n) + "x" + std::to_string(n)};
    CpuStopwatch cpu;
    Stopwatch wall;
    GridErosion grid(Rect::from_size(1.0, 1.0), n, n, tan_alpha());
    grid.pour({0.5, 0.5}, kVolume);
    row.iterations = grid.run_to_rest(400000);
    row.cpu_ms = cpu.ms();
    row.wall_ms = wall.ms();
    row.at_rest = grid.active_count() == 0;
    row.vertices = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    // The poured cell's centre is the apex; compare against the cone centred there.
    const int c = std::clamp(static_cast<int>(0.5 * n), 0, n - 1);
    const Vec2 apex = grid.centre(c, c);
    const Cone cone = Cone::from_volume(kVolume, tan_alpha());
    measure_error(
        row, [&](Vec2 p) { return grid.height_at(p); },
        [&](Vec2 p) { return cone.surface(distance(p, apex)); });
    return row;
}

Row tin_dunes(std::size_t points, const HeightAt& reference, SlopeRule rule) {
    Row row{"dunes", tin_method(rule), std::to_string(points) + " points"};
    row.settle_margin = rule_settings(rule).parameters.settle_margin;
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), points, 21, dunes, TinOptions{false});
    CpuStopwatch cpu;
    Stopwatch wall;
    SandPhysics physics(tin, MaterialTable::presets(), rule_settings(rule));
    physics.activate_all();
    const PhysicsStepReport r = physics.run_to_rest(400000);
    row.cpu_ms = cpu.ms();
    row.wall_ms = wall.ms();
    row.iterations = r.iterations;
    row.at_rest = r.at_rest;
    row.vertices = tin.vertex_count();
    measure_faces(row, tin);
    LocateHint hint;
    measure_error(
        row, [&](Vec2 p) { return *tin.height_at(p, &hint); }, reference);
    return row;
}

struct GridRun {
    Row row;
    std::unique_ptr<GridErosion> grid;
};

GridRun grid_dunes(int n) {
    GridRun g{{"dunes", "grid", std::to_string(n) + "x" + std::to_string(n)}, nullptr};
    CpuStopwatch cpu;
    Stopwatch wall;
    g.grid = std::make_unique<GridErosion>(Rect::from_size(1.0, 1.0), n, n, tan_alpha());
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i)
            g.grid->height(i, j) = dunes(g.grid->centre(i, j));
    }
    g.grid->activate_all();
    g.row.iterations = g.grid->run_to_rest(400000);
    g.row.cpu_ms = cpu.ms();
    g.row.wall_ms = wall.ms();
    g.row.at_rest = g.grid->active_count() == 0;
    g.row.vertices = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    return g;
}

nlohmann::json to_json(const Row& r) {
    return {{"scene", r.scene},
            {"method", r.method},
            {"level", r.level},
            {"vertices", r.vertices},
            {"iterations", r.iterations},
            {"cpu_ms", r.cpu_ms},
            {"wall_ms", r.wall_ms},
            {"mean_error_m", r.mean_error},
            {"max_error_m", r.max_error},
            {"at_rest", r.at_rest},
            {"settle_margin", r.settle_margin},
            {"steep_share_of_slopes",
             r.steep_share < 0.0 ? nlohmann::json() : nlohmann::json(r.steep_share)},
            {"max_face_ratio",
             r.max_face_ratio < 0.0 ? nlohmann::json() : nlohmann::json(r.max_face_ratio)},
            {"skipped_faces",
             r.skipped_faces < 0 ? nlohmann::json() : nlohmann::json(r.skipped_faces)}};
}

/// Jacobi throughput on a regular-grid TIN (999 x 999, about 10⁶ vertices; 200 x 200 with
/// --quick) with a rough surface whose slopes are far above repose, so every vertex stays
/// active: vertex updates per second of wall time over `kTimed` consecutive iterations after a
/// warm-up one (the solver keeps its own active set, as in use), median of `runs` runs.
/// Three numberings of the same graph: the TIN's own ids, the ids renumbered along a Hilbert
/// curve (the TIN's bulk build numbers along CGAL's multiscale spatial sort, which leaves about
/// a third of the neighbours more than 10⁵ ids apart, so every iteration waits on cache
/// misses), and in strips two spacings tall (scanline order).
struct ThroughputScene {
    std::string numbering;
    std::size_t vertices = 0;
    AdjacencyGraph graph;
    std::vector<double> height, area, bedrock;
};

/// Position of (x, y) along a Hilbert curve over a 2^16 x 2^16 lattice.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y) {
    std::uint64_t d = 0;
    for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
        const std::uint32_t rx = (x & s) != 0 ? 1 : 0;
        const std::uint32_t ry = (y & s) != 0 ? 1 : 0;
        d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = s - 1 - (x & (s - 1)) + (x & ~(s - 1));
                y = s - 1 - (y & (s - 1)) + (y & ~(s - 1));
                x &= (s << 1) - 1;
                y &= (s << 1) - 1;
            }
            std::swap(x, y);
        }
    }
    return d;
}

/// The scene's graph with vertex v renamed to the rank of key[v] (ties keep id order).
ThroughputScene renumbered(const ThroughputScene& own, const VertexArrays& va,
                           std::vector<std::pair<std::uint64_t, std::uint32_t>> keys,
                           std::string name) {
    ThroughputScene out;
    out.numbering = std::move(name);
    out.vertices = own.vertices;
    const std::size_t size = keys.size();
    std::sort(keys.begin(), keys.end());
    std::vector<std::uint32_t> new_id(size);
    for (std::uint32_t k = 0; k < size; ++k)
        new_id[keys[k].second] = k;
    std::vector<std::vector<std::uint32_t>> rows(size);
    std::vector<std::vector<double>> lengths(size);
    out.height.resize(size);
    out.area.resize(size);
    out.bedrock.resize(size);
    for (std::uint32_t v = 0; v < size; ++v) {
        const std::uint32_t w = new_id[v];
        out.height[w] = va.height[v];
        out.area[w] = va.lumped_area[v];
        out.bedrock[w] = va.bedrock[v];
        for (std::uint32_t k = own.graph.offset(v); k < own.graph.offset(v) + own.graph.degree(v);
             ++k) {
            rows[w].push_back(new_id[own.graph.targets()[k]]);
            lengths[w].push_back(own.graph.lengths()[k]);
        }
    }
    out.graph.assign(rows, lengths);
    return out;
}

std::vector<ThroughputScene> throughput_scenes(int n) {
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), n, n,
        [](Vec2 p) { return 0.02 * std::sin(400.0 * p.x) * std::cos(300.0 * p.y); },
        TinOptions{false});
    const VertexArrays& va = tin.vertices();
    std::vector<ThroughputScene> scenes;
    scenes.reserve(3);  // `own` refers into it while the others are added
    ThroughputScene& own = scenes.emplace_back();
    own.numbering = "tin ids";
    own.vertices = tin.vertex_count();
    own.graph.rebuild(tin);
    own.height = va.height;
    own.area = va.lumped_area;
    own.bedrock = va.bedrock;

    const std::size_t size = va.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(size);
    for (std::uint32_t v = 0; v < size; ++v) {
        const Vec2 p = va.position[v];  // the domain is the unit square
        keys[v] = {hilbert_index(static_cast<std::uint32_t>(std::clamp(p.x, 0.0, 1.0) * 65535.0),
                                 static_cast<std::uint32_t>(std::clamp(p.y, 0.0, 1.0) * 65535.0)),
                   v};
    }
    scenes.push_back(renumbered(own, va, keys, "hilbert-renumbered"));
    // Strips two vertex spacings tall, each in x order: a vertex's neighbours lie in its own
    // strip or the next one, so the kernels read three or four nearly sequential streams,
    // which the hardware prefetchers follow (a Hilbert curve jumps at every block border).
    const double strip = 2.0 / n;
    for (std::uint32_t v = 0; v < size; ++v) {
        const Vec2 p = va.position[v];
        const auto row = static_cast<std::uint64_t>(std::clamp(p.y, 0.0, 1.0) / strip);
        const auto col = static_cast<std::uint64_t>(std::clamp(p.x, 0.0, 1.0) * 4194303.0);
        keys[v] = {(row << 22) | col, v};
    }
    scenes.push_back(renumbered(own, va, keys, "strips-renumbered"));
    return scenes;
}

double load_average() {
    std::ifstream in("/proc/loadavg");
    double one = -1.0;
    in >> one;
    return one;
}

/// Iterations each throughput run times, after a warm-up one.
constexpr int kTimed = 6;

/// One timed run of jacobi_throughput: wall and CPU seconds of kTimed iterations.
struct ThroughputRun {
    double wall_s = 0.0;
    double cpu_s = 0.0;
    std::size_t updates = 0;
    double rate() const { return static_cast<double>(updates) / wall_s; }
    double cpu_rate() const { return static_cast<double>(updates) / cpu_s; }
};

/// A Jacobi solver over a copy of the scene's heights, with every vertex active.
class SceneSolver {
  public:
    SceneSolver(const ThroughputScene& scene, int threads, RowKernel kernel)
        : scene_(scene),
          height_(scene.height),
          tan_(height_.size(), tan_alpha()),
          solver_(settings(threads, kernel)),
          arrays_{height_.data(), scene.area.data(), scene.bedrock.data(), tan_.data(),
                  height_.size()} {
        for (std::uint32_t v = 0; v < height_.size(); ++v)
            active_.activate(v);
    }
    SceneSolver(const SceneSolver&) = delete;
    SceneSolver& operator=(const SceneSolver&) = delete;

    /// One iteration; the vertices it processed.
    std::size_t iterate() { return solver_.iterate(scene_.graph, arrays_, active_).processed; }
    const TalusSolver& solver() const { return solver_; }

  private:
    static TalusSettings settings(int threads, RowKernel kernel) {
        TalusSettings s;
        s.schedule = Schedule::Jacobi;
        s.threads = threads;
        s.row_kernel = kernel;
        return s;
    }
    const ThroughputScene& scene_;
    std::vector<double> height_;
    std::vector<double> tan_;
    TalusSolver solver_;
    TalusArrays arrays_;
    ActiveSet active_;
};

ThroughputRun time_jacobi(const ThroughputScene& scene, int threads, RowKernel kernel) {
    SceneSolver s(scene, threads, kernel);
    s.iterate();  // warm-up: first-touch of the buffers
    ThroughputRun run;
    const double cpu0 = process_cpu_seconds();
    Stopwatch wall;
    for (int it = 0; it < kTimed; ++it)
        run.updates += s.iterate();
    run.wall_s = wall.ms() * 1e-3;
    run.cpu_s = process_cpu_seconds() - cpu0;
    return run;
}

/// The row kernel RowKernel::Auto settles on for this scene and thread count (it measures both
/// on its first branch-free iteration; a warm-up and one more iteration get there), and whether
/// it measured at all.
std::pair<RowKernel, bool> auto_row_kernel(const ThroughputScene& scene, int threads) {
    SceneSolver s(scene, threads, RowKernel::Auto);
    for (int it = 0; it < 3 && !s.solver().row_kernel_measured(); ++it)
        s.iterate();
    return {s.solver().row_kernel_in_use(), s.solver().row_kernel_measured()};
}

nlohmann::json rates_json(const std::vector<double>& rates, const std::vector<double>& cpu_rates) {
    return {{"vertex_updates_per_s", bench::median(rates)},
            {"vertex_updates_per_cpu_s", bench::median(cpu_rates)},
            {"runs", rates},
            {"runs_per_cpu_s", cpu_rates}};
}

nlohmann::json jacobi_throughput(const ThroughputScene& scene, int threads, int runs) {
    const bool avx512 = avx512_rows_supported();
    std::vector<double> loads;
    // Per kernel: rates per wall second and per CPU second. On an AVX-512 CPU each run times
    // both, next to each other (which goes first alternates), so both see the same machine.
    std::vector<double> avx512_rates, avx512_cpu_rates, sse2_rates, sse2_cpu_rates;
    std::size_t processed = 0;
    for (int run = 0; run < runs; ++run) {
        loads.push_back(load_average());
        auto time = [&](RowKernel kernel) {
            const ThroughputRun r = time_jacobi(scene, threads, kernel);
            processed = r.updates / kTimed;
            const bool sse2 = kernel == RowKernel::Sse2;
            (sse2 ? sse2_rates : avx512_rates).push_back(r.rate());
            (sse2 ? sse2_cpu_rates : avx512_cpu_rates).push_back(r.cpu_rate());
        };
        if (!avx512) {
            time(RowKernel::Sse2);
        } else if (run % 2 == 1) {
            time(RowKernel::Sse2);
            time(RowKernel::Avx512);
        } else {
            time(RowKernel::Avx512);
            time(RowKernel::Sse2);
        }
    }
    // What the physics runs (RowKernel::Auto): the kernel it measured faster.
    const auto [chosen, measured] =
        avx512 ? auto_row_kernel(scene, threads) : std::pair{RowKernel::Sse2, false};
    const bool chose_avx512 = chosen == RowKernel::Avx512;
    const std::vector<double>& rates = chose_avx512 ? avx512_rates : sse2_rates;
    const std::vector<double>& cpu_rates = chose_avx512 ? avx512_cpu_rates : sse2_cpu_rates;
    const double rate = bench::median(rates);
    nlohmann::json out = {
        {"vertices", scene.vertices},
        {"numbering", scene.numbering},
        {"threads", threads},
        {"rows", chose_avx512 ? "avx512" : "sse2"},
        {"rows_measured", measured},
        {"processed_per_iteration", processed},
        {"vertex_updates_per_s", rate},
        {"vertex_updates_per_s_per_core", rate / threads},
        {"runs", rates},
        // Updates per second of CPU time summed over the threads: the per-core rate with
        // the time the other agents' processes took from us left out.
        {"vertex_updates_per_cpu_s", bench::median(cpu_rates)},
        {"runs_per_cpu_s", cpu_rates},
        {"load_average_1min", loads},
        {"timer", "wall time of " + std::to_string(kTimed) +
                      " consecutive iterations after a warm-up one, median of " +
                      std::to_string(runs) + " runs (other agents share the 2 cores)"}};
    if (avx512) {
        out["avx512_rows"] = rates_json(avx512_rates, avx512_cpu_rates);
        out["sse2_rows"] = rates_json(sse2_rates, sse2_cpu_rates);
        out["avx512_over_sse2"] = bench::median(avx512_rates) / bench::median(sse2_rates);
    }
    return out;
}

nlohmann::json jacobi_throughputs(bool quick, int runs) {
    const std::vector<ThroughputScene> scenes = throughput_scenes(quick ? 200 : 999);
    nlohmann::json list = nlohmann::json::array();
    for (const ThroughputScene& scene : scenes) {
        for (int threads : {1, 2})
            list.push_back(jacobi_throughput(scene, threads, runs));
    }
    return list;
}

/// The same 10⁶-vertex rough scene relaxed through SandPhysics (Jacobi), in the TIN's ids and
/// in the physics' own strip numbering: what a real scene gets, including the per-step sync
/// and the write-back of the heights into the TIN. Each run restores the heights, builds a
/// fresh SandPhysics (not timed), takes one warm-up iteration and then times one step of
/// `kTimed` iterations; updates per CPU-second, median of `runs`.
nlohmann::json sand_physics_throughputs(bool quick, int runs) {
    const int n = quick ? 200 : 999;
    Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), n, n,
        [](Vec2 p) { return 0.02 * std::sin(400.0 * p.x) * std::cos(300.0 * p.y); },
        TinOptions{false});
    std::vector<VertexId> ids;
    std::vector<double> initial;
    for (std::uint32_t v = 0; v < tin.vertices().size(); ++v) {
        if (!tin.vertices().alive[v]) continue;
        ids.push_back(VertexId{v});
        initial.push_back(tin.vertices().height[v]);
    }
    nlohmann::json list = nlohmann::json::array();
    for (VertexOrder order : {VertexOrder::Tin, VertexOrder::Strips}) {
        for (int threads : {1, 2}) {
            std::vector<double> cpu_rates;
            std::size_t per_iteration = 0;
            for (int run = 0; run < runs; ++run) {
                tin.set_heights(ids, initial);
                TalusSettings settings;
                settings.schedule = Schedule::Jacobi;
                settings.threads = threads;
                SandPhysics physics(tin, MaterialTable::presets(), settings, order);
                physics.activate_all();
                physics.step(1);
                const double cpu0 = process_cpu_seconds();
                const PhysicsStepReport r = physics.step(kTimed);
                const double cpu_s = process_cpu_seconds() - cpu0;
                per_iteration = r.vertex_updates / static_cast<std::size_t>(kTimed);
                cpu_rates.push_back(static_cast<double>(r.vertex_updates) / cpu_s);
            }
            list.push_back(
                {{"vertices", ids.size()},
                 {"numbering",
                  order == VertexOrder::Tin ? "sand-physics tin ids" : "sand-physics strips"},
                 {"threads", threads},
                 {"processed_per_iteration", per_iteration},
                 {"vertex_updates_per_cpu_s", bench::median(cpu_rates)},
                 {"runs_per_cpu_s", cpu_rates},
                 {"timer", "CPU time of one SandPhysics::step(" + std::to_string(kTimed) +
                               ") after a warm-up iteration, median of " + std::to_string(runs) +
                               " runs"}});
        }
    }
    return list;
}

void write_csv(const std::filesystem::path& path, const std::vector<Row>& rows) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    out << "scene,method,level,vertices,iterations,cpu_ms,wall_ms,mean_error_m,max_error_m,at_"
           "rest,steep_share_of_slopes,max_face_ratio,skipped_faces\n";
    for (const Row& r : rows) {
        out << r.scene << ',' << r.method << ',' << r.level << ',' << r.vertices << ','
            << r.iterations << ',' << r.cpu_ms << ',' << r.wall_ms << ',' << r.mean_error << ','
            << r.max_error << ',' << (r.at_rest ? 1 : 0) << ',';
        // Empty fields on grid rows, which have no faces of their own.
        if (r.steep_share >= 0.0) out << r.steep_share;
        out << ',';
        if (r.max_face_ratio >= 0.0) out << r.max_face_ratio;
        out << ',';
        if (r.skipped_faces >= 0) out << r.skipped_faces;
        out << '\n';
    }
}

/// Log-log plot of CPU time to rest (x) against mean error (y), one panel per scene.
void write_svg(const std::filesystem::path& path, const std::vector<Row>& rows) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    const int w = 420, h = 320, m = 50;
    out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << 2 * w << "' height='" << h
        << "' font-family='sans-serif' font-size='11'>\n";
    int panel = 0;
    for (const std::string scene : {"cone", "dunes"}) {
        double tx0 = 1e300, tx1 = 0, ey0 = 1e300, ey1 = 0;
        for (const Row& r : rows) {
            if (r.scene != scene) continue;
            tx0 = std::min(tx0, r.cpu_ms), tx1 = std::max(tx1, r.cpu_ms);
            ey0 = std::min(ey0, r.mean_error), ey1 = std::max(ey1, r.mean_error);
        }
        if (tx1 <= 0) continue;
        const double lx0 = std::log10(tx0) - 0.2, lx1 = std::log10(tx1) + 0.2;
        const double ly0 = std::log10(std::max(ey0, 1e-12)) - 0.2, ly1 = std::log10(ey1) + 0.2;
        const int ox = panel * w;
        auto X = [&](double t) {
            return ox + m + (std::log10(t) - lx0) / (lx1 - lx0) * (w - 2 * m);
        };
        auto Y = [&](double e) {
            return h - m - (std::log10(std::max(e, 1e-12)) - ly0) / (ly1 - ly0) * (h - 2 * m);
        };
        out << "<rect x='" << ox + m << "' y='" << m << "' width='" << w - 2 * m << "' height='"
            << h - 2 * m << "' fill='none' stroke='black'/>\n";
        out << "<text x='" << ox + w / 2 << "' y='20' text-anchor='middle'>" << scene
            << ": CPU ms to rest (log) vs mean |dz| m (log)</text>\n";
        out << "<text x='" << ox + m << "' y='" << h - m + 15 << "'>" << tx0 << " ms</text>\n";
        out << "<text x='" << ox + w - m << "' y='" << h - m + 15 << "' text-anchor='end'>" << tx1
            << " ms</text>\n";
        out << "<text x='" << ox + 2 << "' y='" << m + 10 << "'>" << ey1 << "</text>\n";
        out << "<text x='" << ox + 2 << "' y='" << h - m << "'>" << ey0 << "</text>\n";
        for (const std::string method : {"tin", "tin-face", "grid"}) {
            const char* colour = method == "tin"        ? "#c0392b"
                                 : method == "tin-face" ? "#27ae60"
                                                        : "#2c3e50";
            std::string poly;
            for (const Row& r : rows) {
                if (r.scene != scene || r.method != method) continue;
                poly += std::to_string(X(r.cpu_ms)) + "," + std::to_string(Y(r.mean_error)) + " ";
                out << "<circle cx='" << X(r.cpu_ms) << "' cy='" << Y(r.mean_error)
                    << "' r='4' fill='" << colour << "'><title>" << r.level << ", " << r.vertices
                    << " vertices</title></circle>\n";
            }
            out << "<polyline points='" << poly << "' fill='none' stroke='" << colour << "'/>\n";
        }
        out << "<text x='" << ox + w - m - 80 << "' y='" << m + 15
            << "' fill='#c0392b'>TIN, edges</text>"
            << "<text x='" << ox + w - m - 80 << "' y='" << m + 30
            << "' fill='#27ae60'>TIN, faces</text>"
            << "<text x='" << ox + w - m - 80 << "' y='" << m + 45
            << "' fill='#2c3e50'>grid</text>\n";
        ++panel;
    }
    out << "</svg>\n";
}

}  // namespace

int run_bench_erosion(const std::vector<std::string>& raw) {
    const Arguments args(raw, {{"--quick", 0}, {"--json", 0}, {"--out", 1}, {"--throughput", 0}});
    args.require_positionals(1,
                             "sandtin bench erosion [--quick] [--json] [--out DIR] [--throughput]");
    const bool quick = args.has("--quick");
    ProgressLine progress("bench erosion");
    // Progress counts sections (one run of a scene at a resolution, or a throughput table).
    std::size_t sections = 0;
    std::size_t sections_done = 0;
    const auto section = [&](const std::string& name) {
        progress.report(
            {static_cast<double>(sections_done++) / static_cast<double>(sections), name});
    };
    if (args.has("--throughput")) {
        // Only the Jacobi throughput (issue 4's 10⁶-vertex figure), 5 runs per thread count.
        sections = 2;
        nlohmann::json j;
        j["bench"] = "erosion";
        section("Jacobi throughput");
        j["jacobi_throughput"] = jacobi_throughputs(quick, 5);
        section("sand physics throughput");
        j["sand_physics_throughput"] = sand_physics_throughputs(quick, 5);
        progress.finish();
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    const int repeats = quick ? 1 : 3;
    std::vector<Row> rows;

    const std::vector<double> tin_rs =
        quick ? std::vector<double>{0.04} : std::vector<double>{0.04, 0.02, 0.01};
    const std::vector<int> grid_n =
        quick ? std::vector<int>{32} : std::vector<int>{32, 64, 128, 256};
    const std::vector<std::size_t> tin_points =
        quick ? std::vector<std::size_t>{1000} : std::vector<std::size_t>{2000, 8000, 32000};
    const std::vector<int> dune_n = quick ? std::vector<int>{16} : std::vector<int>{32, 64, 128};
    // The runs, the dunes' reference grid and the two throughput tables.
    // Each TIN run under both slope rules (edges, then faces).
    const SlopeRule rules[] = {SlopeRule::Edge, SlopeRule::Face};
    sections = 2 * tin_rs.size() + grid_n.size() + 1 + 2 * tin_points.size() + dune_n.size() + 2;
    for (SlopeRule rule : rules) {
        for (double rs : tin_rs) {
            std::ostringstream stage;
            stage << "cone on the TIN (" << tin_method(rule) << "), r_S " << rs << " m";
            section(stage.str());
            rows.push_back(median_of(repeats, [&] { return tin_cone(rs, rule); }));
        }
    }
    for (int n : grid_n) {
        section("cone on a " + std::to_string(n) + "² grid");
        rows.push_back(median_of(repeats, [&] { return grid_cone(n); }));
    }

    // Dunes: the finest grid is the reference.
    const int ref_n = quick ? 64 : 256;
    section("dunes: the " + std::to_string(ref_n) + "² reference grid");
    GridRun ref = grid_dunes(ref_n);
    const GridErosion& ref_grid = *ref.grid;
    const HeightAt reference = [&](Vec2 p) { return ref_grid.height_at(p); };
    for (SlopeRule rule : rules) {
        for (std::size_t pts : tin_points) {
            section("dunes on a " + std::to_string(pts) + "-point TIN (" + tin_method(rule) + ")");
            rows.push_back(median_of(repeats, [&] { return tin_dunes(pts, reference, rule); }));
        }
    }
    for (int n : dune_n) {
        section("dunes on a " + std::to_string(n) + "² grid");
        rows.push_back(median_of(repeats, [&] {
            GridRun g = grid_dunes(n);
            measure_error(
                g.row, [&](Vec2 p) { return g.grid->height_at(p); }, reference);
            return g.row;
        }));
    }

    nlohmann::json j;
    j["bench"] = "erosion";
    j["repeats"] = repeats;
    j["timer"] = "thread CPU time, median of repeats; wall time alongside";
    j["dunes_reference"] = {{"grid", ref_n}, {"cpu_ms", ref.row.cpu_ms}};
    nlohmann::json list = nlohmann::json::array();
    for (const Row& r : rows)
        list.push_back(to_json(r));
    j["runs"] = list;

    // Cone target: the TIN's cheapest run reaching the grid's best error.
    const Row* best_grid = nullptr;
    for (const Row& r : rows) {
        if (r.scene == "cone" && r.method == "grid" &&
            (best_grid == nullptr || r.mean_error < best_grid->mean_error))
            best_grid = &r;
    }
    const Row* tin_match = nullptr;
    for (const Row& r : rows) {
        if (r.scene == "cone" && r.method.starts_with("tin") && best_grid != nullptr &&
            r.mean_error <= best_grid->mean_error &&
            (tin_match == nullptr || r.cpu_ms < tin_match->cpu_ms))
            tin_match = &r;
    }
    nlohmann::json target = {{"grid_best", best_grid ? to_json(*best_grid) : nlohmann::json()}};
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
    j["cone_target"] = target;
    section("Jacobi throughput");
    j["jacobi_throughput"] = jacobi_throughputs(quick, 3);
    section("sand physics throughput");
    j["sand_physics_throughput"] = sand_physics_throughputs(quick, 3);
    progress.finish();

    if (args.has("--out")) {
        const std::filesystem::path dir = args.text("--out");
        std::filesystem::create_directories(dir);
        write_csv(dir / "erosion.csv", rows);
        write_svg(dir / "erosion.svg", rows);
        j["csv"] = (dir / "erosion.csv").string();
        j["svg"] = (dir / "erosion.svg").string();
    }
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace sandtin::cli
