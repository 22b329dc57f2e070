// The Jacobi throughput tables of `sandtin bench erosion` (bench_erosion_throughput.hpp).

#include "bench_erosion_throughput.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "bench_erosion_run.hpp"
#include "physics/adjacency_graph.hpp"
#include "physics/sand_physics.hpp"
#include "physics/talus_kernel_avx512.hpp"
#include "physics/talus_solver.hpp"
#include "tin/tin.hpp"
#include "util/process_cpu_time.hpp"

namespace sandtin::cli {

namespace {

using bench::CpuStopwatch;
using bench::Stopwatch;

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
    std::vector<std::vector<double>> lengths(size), across(size);
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
            across[w].push_back(own.graph.across()[k]);  // the row's order is kept: its faces too
        }
    }
    out.graph.assign(rows, lengths, &across);
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
    SceneSolver(const ThroughputScene& scene, SlopeRule rule, int threads, RowKernel kernel)
        : scene_(scene),
          height_(scene.height),
          tan_(height_.size(), dry_sand_tan_alpha()),
          solver_(settings(rule, threads, kernel)),
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
    static TalusSettings settings(SlopeRule rule, int threads, RowKernel kernel) {
        TalusSettings s;
        s.parameters.rule = rule;
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

ThroughputRun time_jacobi(const ThroughputScene& scene, SlopeRule rule, int threads,
                          RowKernel kernel) {
    SceneSolver s(scene, rule, threads, kernel);
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
    SceneSolver s(scene, SlopeRule::Edge, threads, RowKernel::Auto);
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

/// Under the face rule the rows always branch (no SSE2 or AVX-512 row passes): one kernel.
nlohmann::json jacobi_throughput(const ThroughputScene& scene, SlopeRule rule, int threads,
                                 int runs) {
    const bool avx512 = rule == SlopeRule::Edge && avx512_rows_supported();
    std::vector<double> loads;
    // Per kernel: rates per wall second and per CPU second. On an AVX-512 CPU each run times
    // both, next to each other (which goes first alternates), so both see the same machine.
    std::vector<double> avx512_rates, avx512_cpu_rates, sse2_rates, sse2_cpu_rates;
    std::size_t processed = 0;
    for (int run = 0; run < runs; ++run) {
        loads.push_back(load_average());
        auto time = [&](RowKernel kernel) {
            const ThroughputRun r = time_jacobi(scene, rule, threads, kernel);
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
        {"rule", rule == SlopeRule::Face ? "face" : "edge"},
        {"threads", threads},
        {"rows", rule == SlopeRule::Face ? "branching"
                 : chose_avx512          ? "avx512"
                                         : "sse2"},
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

}  // namespace

nlohmann::json jacobi_throughputs(bool quick, int runs) {
    const std::vector<ThroughputScene> scenes = throughput_scenes(quick ? 200 : 999);
    nlohmann::json list = nlohmann::json::array();
    for (const ThroughputScene& scene : scenes) {
        for (SlopeRule rule : {SlopeRule::Edge, SlopeRule::Face}) {
            for (int threads : {1, 2})
                list.push_back(jacobi_throughput(scene, rule, threads, runs));
        }
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
        for (SlopeRule rule : {SlopeRule::Edge, SlopeRule::Face}) {
            for (int threads : {1, 2}) {
                std::vector<double> cpu_rates;
                std::size_t per_iteration = 0;
                for (int run = 0; run < runs; ++run) {
                    tin.set_heights(ids, initial);
                    TalusSettings settings;
                    settings.schedule = Schedule::Jacobi;
                    settings.threads = threads;
                    settings.parameters.rule = rule;
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
                     {"rule", rule == SlopeRule::Face ? "face" : "edge"},
                     {"threads", threads},
                     {"processed_per_iteration", per_iteration},
                     {"vertex_updates_per_cpu_s", bench::median(cpu_rates)},
                     {"runs_per_cpu_s", cpu_rates},
                     {"timer", "CPU time of one SandPhysics::step(" + std::to_string(kTimed) +
                                   ") after a warm-up iteration, median of " +
                                   std::to_string(runs) + " runs"}});
            }
        }
    }
    return list;
}

}  // namespace sandtin::cli
