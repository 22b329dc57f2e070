#include "bench_tin.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <stdexcept>

#include "io/session_file.hpp"
#include "io/session_terrain.hpp"
#include "raw_cgal.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"

namespace sandtin::bench {

namespace {

std::vector<Vec2> random_square_points(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec2> pts = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    pts.reserve(n + 4);
    for (std::size_t i = 0; i < n; ++i)
        pts.push_back({u(rng), u(rng)});
    return pts;
}

/// A smooth random walk inside the unit square: consecutive points 1 mm to 1 cm apart, like a
/// tool path.
std::vector<Vec2> walk(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec2> out;
    Vec2 p{0.5, 0.5};
    double heading = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        heading += 0.3 * u(rng);
        p += Vec2{std::cos(heading), std::sin(heading)} * (0.0055 + 0.0045 * u(rng));
        if (p.x < 0.05 || p.x > 0.95 || p.y < 0.05 || p.y > 0.95) {
            heading += std::numbers::pi;
            p.x = std::clamp(p.x, 0.05, 0.95);
            p.y = std::clamp(p.y, 0.05, 0.95);
        }
        out.push_back(p);
    }
    return out;
}

std::vector<Vec2> ring(Vec2 centre, double radius, int points) {
    std::vector<Vec2> r;
    for (int i = 0; i < points; ++i) {
        const double a = 2.0 * std::numbers::pi * i / points;
        r.push_back(centre + Vec2{std::cos(a), std::sin(a)} * radius);
    }
    return r;
}

int insert_repetitions(const BenchConfig& config, std::size_t n) {
    return config.quick ? 2 : (n >= 1000000 ? 7 : 9);
}

nlohmann::json bench_insert(const BenchConfig& config, const ProgressCallback& part) {
    nlohmann::json rows = nlohmann::json::array();
    const std::vector<std::size_t> sizes = config.quick
                                               ? std::vector<std::size_t>{1000, 10000}
                                               : std::vector<std::size_t>{10000, 100000, 1000000};
    double work = 0.0;  // a build costs about its point count
    for (std::size_t n : sizes)
        work += static_cast<double>(n) * insert_repetitions(config, n);
    WeightedProgress progress(part, work);
    for (std::size_t n : sizes) {
        const std::vector<Vec2> pts = random_square_points(n, 42);
        const std::vector<double> zeros(pts.size(), 0.0);
        const int reps = insert_repetitions(config, n);
        std::vector<double> ours, raw, ours_cpu, raw_cpu;
        for (int r = 0; r < reps; ++r) {
            progress.start("inserting " + std::to_string(n) + " points, run " +
                               std::to_string(r + 1) + " of " + std::to_string(reps),
                           static_cast<double>(n));
            {  // interleaved, so both see the same machine state
                Stopwatch w;
                CpuStopwatch c;
                Tin tin = Tin::from_points(Rect::from_size(1, 1), pts, zeros);
                ours.push_back(w.ms());
                ours_cpu.push_back(c.ms());
            }
            {
                Stopwatch w;
                CpuStopwatch c;
                RawCgalTin cgal;
                cgal.insert(pts);
                raw.push_back(w.ms());
                raw_cpu.push_back(c.ms());
            }
        }
        const double mo = median(ours), mr = median(raw);
        const double co = median(ours_cpu), cr = median(raw_cpu);
        rows.push_back({{"points", n},
                        {"repetitions", reps},
                        {"sandtin_ms", mo},
                        {"cgal_ms", mr},
                        {"ratio", mo / mr},
                        {"sandtin_cpu_ms", co},
                        {"cgal_cpu_ms", cr},
                        {"cpu_ratio", co / cr}});
    }
    return rows;
}

nlohmann::json bench_locate(const BenchConfig& config) {
    const std::size_t n = config.quick ? 10000 : 1000000;
    const std::size_t q = config.quick ? 2000 : 100000;
    const std::vector<Vec2> pts = random_square_points(n, 7);
    const std::vector<double> zeros(pts.size(), 0.0);
    Tin tin = Tin::from_points(Rect::from_size(1, 1), pts, zeros);
    RawCgalTin cgal;
    cgal.insert(pts);
    const std::vector<Vec2> path = walk(q, 11);
    std::vector<Vec2> scattered = random_square_points(q, 13);
    scattered.erase(scattered.begin(), scattered.begin() + 4);

    double checksum = 0.0;
    auto time_ns = [&](auto&& body) {
        std::vector<double> t;
        for (int r = 0; r < 3; ++r) {
            Stopwatch w;
            body();
            t.push_back(w.ms() * 1e6 / static_cast<double>(q));
        }
        return median(t);
    };
    const double hinted = time_ns([&] {
        LocateHint hint;
        for (Vec2 p : path)
            checksum += tin.locate(p, &hint).barycentric[0];
    });
    const double path_unhinted = time_ns([&] {
        for (Vec2 p : path)
            checksum += tin.locate(p).barycentric[0];
    });
    const double scattered_unhinted = time_ns([&] {
        for (Vec2 p : scattered)
            checksum += tin.locate(p).barycentric[0];
    });
    const double cgal_path =
        time_ns([&] { checksum += static_cast<double>(cgal.locate_all(path)); });
    return {{"points", n},
            {"queries", q},
            {"path_with_hint_ns", hinted},
            {"path_without_hint_ns", path_unhinted},
            {"scattered_without_hint_ns", scattered_unhinted},
            {"cgal_default_start_path_ns", cgal_path},
            {"checksum", checksum}};
}

nlohmann::json bench_remove(const BenchConfig& config) {
    const std::size_t n = config.quick ? 10000 : 100000;
    const std::size_t removals = n / 10;
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::random_points(
        Rect::from_size(1, 1), n, 5, [](Vec2 p) { return 0.1 * p.x * p.y; }, options);
    std::mt19937_64 rng(3);
    std::vector<VertexId> doomed;
    for (std::uint32_t i = 0; i < tin.vertex_capacity() && doomed.size() < removals; i += 7) {
        const VertexId v{i};
        if (tin.is_alive(v) && !tin.is_boundary(v)) doomed.push_back(v);
    }
    std::shuffle(doomed.begin(), doomed.end(), rng);
    Stopwatch w;
    std::size_t removed = 0;
    for (VertexId v : doomed)
        removed += tin.remove_vertex(v) ? 1 : 0;
    const double ms = w.ms();
    return {{"points", n},
            {"removed", removed},
            {"us_per_removal", ms * 1e3 / static_cast<double>(removed)}};
}

nlohmann::json bench_constraints(const BenchConfig& config) {
    const std::size_t n = config.quick ? 10000 : 1000000;
    const std::size_t rings = config.quick ? 50 : 400;
    const std::vector<Vec2> pts = random_square_points(n, 9);
    const std::vector<double> zeros(pts.size(), 0.0);
    Tin tin = Tin::from_points(Rect::from_size(1, 1), pts, zeros);
    RawCgalTin cgal;
    cgal.insert(pts);
    RawCgalPlusTin cgal_plus;
    cgal_plus.insert(pts);
    // Rings of radius 0.04 every 0.01 m along a path: each crosses the previous three.
    const std::vector<Vec2> centres = walk(rings, 17);
    std::vector<double> ours, raw, raw_plus;
    LocateHint hint;
    Generation generation = 1;
    for (Vec2 c : centres) {
        const std::vector<Vec2> r = ring(c, 0.04, 12);
        {
            Stopwatch w;
            std::vector<VertexId> ids;
            for (Vec2 p : r)
                ids.push_back(tin.insert_point_on_surface(p, &hint));
            tin.insert_constraint(ids, true, generation++);
            ours.push_back(w.ms());
        }
        {
            Stopwatch w;
            cgal.constrain_ring(r);
            raw.push_back(w.ms());
        }
        {
            Stopwatch w;
            cgal_plus.constrain_ring(r);
            raw_plus.push_back(w.ms());
        }
        tin.take_changes();
    }
    return {{"points", n},
            {"rings", rings},
            {"ring_points", 12},
            {"sandtin_ms_per_ring_median", median(ours)},
            {"cgal_ms_per_ring_median", median(raw)},
            {"ratio", median(ours) / median(raw)},
            // CGAL with the constraint hierarchy sandtin keeps: what the TIN's own bookkeeping
            // adds, apart from the hierarchy.
            {"cgal_plus_ms_per_ring_median", median(raw_plus)},
            {"ratio_to_cgal_plus", median(ours) / median(raw_plus)},
            {"constrained_edges_after", tin.constrained_edge_count()},
            {"vertices_after", tin.vertex_count()},
            {"cgal_vertices_after", cgal.vertex_count()}};
}

/// Saving a terrain as a session (its snapshot, encoded and written atomically), then opening
/// it: reading and checking the file (load_session) and rebuilding the terrain with every
/// validity check (take_session_terrain), in wall time, since the rebuild runs its independent
/// checks on every core. Medians of three.
nlohmann::json bench_save_and_open(const Tin& tin) {
    namespace fs = std::filesystem;
    const fs::path file =
        fs::temp_directory_path() / ("sandtin-bench-open-" + std::to_string(tin.vertex_count()) +
                                     "-" + std::to_string(std::random_device{}()) + ".sandtin");
    std::vector<double> save;
    for (int rep = 0; rep < 3; ++rep) {
        const Stopwatch w;
        Session session;
        session.terrain = tin.snapshot();
        save_session(file, session);
        save.push_back(w.ms());
    }
    const auto bytes = fs::file_size(file);
    TinOptions options;
    options.track_changes = false;
    std::vector<double> load, rebuild, open;
    for (int rep = 0; rep < 3; ++rep) {
        const Stopwatch whole;
        Session loaded = load_session(file);
        load.push_back(whole.ms());
        const Stopwatch w;
        const Tin opened = take_session_terrain(loaded, file, options);
        rebuild.push_back(w.ms());
        open.push_back(whole.ms());
        if (opened.vertex_count() != tin.vertex_count())
            throw std::runtime_error("bench open: the terrain opened is not the one saved");
    }
    fs::remove(file);
    return {{"file_bytes", bytes},
            {"save_wall_ms_median", median(save)},
            {"load_wall_ms_median", median(load)},
            {"rebuild_wall_ms_median", median(rebuild)},
            {"open_wall_ms_median", median(open)}};
}

/// Rebuilding a terrain from its snapshot (what loading a session does after parsing the
/// file), split into the rebuild and the full validity check that ends it, then opening the
/// same terrain saved as a session.
nlohmann::json bench_restore(const BenchConfig& config, const ProgressCallback& part) {
    nlohmann::json rows = nlohmann::json::array();
    const std::vector<std::size_t> sizes =
        config.quick ? std::vector<std::size_t>{10000} : std::vector<std::size_t>{100000, 1000000};
    double work = 0.0;
    for (std::size_t n : sizes)
        work += static_cast<double>(n);
    WeightedProgress progress(part, work);
    for (std::size_t n : sizes) {
        progress.start("restoring " + std::to_string(n) + " vertices from a snapshot",
                       static_cast<double>(n));
        TinOptions options;
        options.track_changes = false;
        const Tin original = Tin::random_points(
            Rect::from_size(1, 1), n, 11, [](Vec2 p) { return 0.1 * p.x * p.y; }, options);
        CpuStopwatch snap_watch;
        const TinSnapshot snapshot = original.snapshot();
        const double snapshot_ms = snap_watch.ms();
        std::vector<double> restore, validate;
        std::size_t vertices = 0;
        for (int rep = 0; rep < 3; ++rep) {
            CpuStopwatch w;
            const Tin restored = Tin::from_snapshot(snapshot, options);
            restore.push_back(w.ms());
            CpuStopwatch v;
            if (!restored.check_valid().ok()) throw std::runtime_error("bench restore: invalid");
            validate.push_back(v.ms());
            vertices = restored.vertex_count();
        }
        nlohmann::json row = {{"points", n},
                              {"vertices", vertices},
                              {"snapshot_cpu_ms", snapshot_ms},
                              {"restore_cpu_ms_median", median(restore)},
                              {"check_valid_cpu_ms_median", median(validate)}};
        row["open"] = bench_save_and_open(original);
        rows.push_back(std::move(row));
    }
    progress.done();
    return rows;
}

}  // namespace

nlohmann::json bench_tin(const BenchConfig& config) {
    nlohmann::json j;
    j["bench"] = "tin";
    j["quick"] = config.quick;
    // The parts' shares of a full run (about 110 s on the 2-core reference machine).
    const ProgressCallback& p = config.progress;
    j["insert"] = bench_insert(config, progress_part(p, 0.0, 0.5));
    if (p) p({0.5, "point location"});
    j["locate"] = bench_locate(config);
    if (p) p({0.7, "vertex removal"});
    j["remove"] = bench_remove(config);
    if (p) p({0.71, "rings of crossing constraints"});
    j["constraints"] = bench_constraints(config);
    j["restore"] = bench_restore(config, progress_part(p, 0.8, 1.0));
    return j;
}

}  // namespace sandtin::bench
