#include "stress/stress_runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "io/script.hpp"
#include "io/session_file.hpp"
#include "stress/minimise_failing_sequence.hpp"
#include "stress/random_operation.hpp"
#include "stress/terrain_invariants.hpp"
#include "util/json_fields.hpp"

namespace sandtin {

namespace {

constexpr const char* kSaveName = "stress.sandtin";

std::string scientific(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", x);
    return buf;
}

Script parse_header(nlohmann::json header, const std::filesystem::path& work_dir) {
    header["operations"] = nlohmann::json::array();
    return parse_script(header.dump(), "stress", work_dir);
}

/// One terrain with its sculpting context and script runner, fed one operation at a time.
class StressSession {
  public:
    struct Outcome {
        std::optional<std::string> rejection;  ///< the parser refused the operation
        std::optional<InvariantViolation> violation;
        double volume_residual = 0.0;  ///< relative
        bool fully_checked = false;    ///< the triangulation's full validity check ran
    };

    StressSession(const nlohmann::json& header, const std::filesystem::path& work_dir,
                  const StressOptions& options)
        : work_dir_(work_dir),
          settings_(header.at("settings")),
          script_(parse_header(header, work_dir)),
          tin_(make_script_terrain(*script_.terrain)),
          context_(tin_.domain()),
          runner_(script_, tin_, context_, /*with_physics=*/true),
          tolerance_(options.volume_tolerance),
          volume_(tin_.volume()) {
        // Long sessions must plateau: a tool stamp leaves at most a few hundred vertices and
        // simplification and re-stamping reclaim them, so the counts stay within a fixed
        // multiple of what the terrain started with plus a density cap of one vertex per
        // (2 mm)² of domain (the finest rim sampling the generated tools use).
        const double area = tin_.domain().width() * tin_.domain().height();
        limits_.max_vertices = 4 * tin_.vertex_count() + static_cast<std::size_t>(area / 4e-6);
        limits_.max_constraints = 4096;
        if (options.limits) limits_ = *options.limits;
    }

    const Tin& tin() const { return tin_; }

    /// Runs `op` and checks the invariants; the triangulation's full check only when
    /// `triangulation` is full (a save is always fully checked: it is reloaded and compared).
    Outcome apply(const nlohmann::json& op, TriangulationCheck triangulation) {
        Outcome out;
        if (op.value("op", "") == "save") triangulation = TriangulationCheck::full;
        out.fully_checked = triangulation == TriangulationCheck::full;
        const nlohmann::json one = {{"version", 1}, {"settings", settings_}, {"operations", {op}}};
        Script script;
        try {
            script = parse_script(one.dump(2), "stress", work_dir_);
        } catch (const JsonInputError& e) {
            out.rejection = e.what();
            return out;
        }
        const double before = volume_;
        nlohmann::json report = nlohmann::json::object();
        try {
            report = runner_.run(script.steps.front());
        } catch (const std::invalid_argument& e) {
            // Input only the terrain shows to be bad (a tool too small for its size): a clear
            // refusal, after which every invariant below must still hold and the volume must
            // be as it was.
            out.rejection = e.what();
        } catch (const std::exception& e) {
            out.violation = InvariantViolation{"exception", e.what()};
            return out;
        }
        // Consume the change journal like the GPU mirror does each frame: it recycles freed ids,
        // and its ranges must stay inside the arrays.
        const ChangeSet changes = tin_.take_changes();
        if ((out.violation = check_change_set(changes))) return out;
        if ((out.violation = check_terrain_invariants(tin_, context_.peek_generation(), limits_,
                                                      triangulation)))
            return out;
        const double after = tin_.volume();
        volume_ = after;  // recomputed from scratch once per operation, reused as the next before
        const double reported = report.value("volume_change", 0.0);
        const double scale =
            std::abs(before) + std::abs(reported) + tin_.domain().width() * tin_.domain().height();
        out.volume_residual = std::abs((after - before) - reported) / scale;
        if (!(out.volume_residual <= tolerance_)) {
            out.violation = InvariantViolation{
                "volume", "the volume changed by " + scientific(after - before) +
                              " m³ but the operation reported " + scientific(reported) +
                              " m³ (relative residual " + scientific(out.volume_residual) + ")"};
            return out;
        }
        if (report.value("op", "") == "save") out.violation = check_save_load();
        return out;
    }

  private:
    static std::optional<InvariantViolation> check_change_set(const ChangeSet& c) {
        for (const IdRange& r : c.vertices) {
            if (r.begin >= r.end || r.end > c.vertex_capacity)
                return InvariantViolation{"journal",
                                          "a dirty vertex range lies outside the arrays"};
        }
        for (const IdRange& r : c.triangles) {
            if (r.begin >= r.end || r.end > c.slot_capacity)
                return InvariantViolation{"journal",
                                          "a dirty triangle range lies outside the slots"};
        }
        if (c.live_slots + c.dead_slots != c.slot_capacity)
            return InvariantViolation{"journal",
                                      "live and dead slots do not add up to the capacity"};
        return std::nullopt;
    }

    std::optional<InvariantViolation> check_save_load() {
        Session current;
        current.terrain = tin_.snapshot();
        current.next_generation = context_.peek_generation();
        const std::vector<std::uint8_t> expected = encode_session(current);
        try {
            const Session loaded = load_session(work_dir_ / kSaveName);
            if (encode_session(loaded) != expected) {
                return InvariantViolation{"save_load",
                                          "the saved session does not load back unchanged"};
            }
            Session rebuilt = loaded;
            rebuilt.terrain = Tin::from_snapshot(loaded.terrain).snapshot();
            if (encode_session(rebuilt) != expected) {
                return InvariantViolation{
                    "save_load",
                    "a terrain rebuilt from the saved session differs from the original"};
            }
        } catch (const std::exception& e) {
            return InvariantViolation{"save_load", std::string("loading failed: ") + e.what()};
        }
        return std::nullopt;
    }

    std::filesystem::path work_dir_;
    nlohmann::json settings_;
    Script script_;
    Tin tin_;
    SculptContext context_;
    ScriptRunner runner_;
    InvariantLimits limits_;
    double tolerance_;
    double volume_;  ///< the terrain's volume after the last operation (m³)
};

struct Replay {
    std::size_t index = 0;
    InvariantViolation violation;
};

/// Replays `ops` on a fresh session; the first violation, if any.
std::optional<Replay> replay(const nlohmann::json& header, const std::vector<nlohmann::json>& ops,
                             const std::filesystem::path& work_dir, const StressOptions& options) {
    StressSession session(header, work_dir, options);
    for (std::size_t k = 0; k < ops.size(); ++k) {
        StressSession::Outcome o = session.apply(ops[k], TriangulationCheck::full);
        if (o.violation) return Replay{k, *o.violation};
    }
    return std::nullopt;
}

/// A directory of our own for save files, removed on exit.
class WorkDir {
  public:
    explicit WorkDir(const std::filesystem::path& given, std::uint64_t seed) {
        if (!given.empty()) {
            path_ = given;
            std::filesystem::create_directories(path_);
            return;
        }
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() /
                ("sandtin-stress-" + std::to_string(seed) + "-" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
        owned_ = true;
    }
    ~WorkDir() {
        if (owned_) {
            std::error_code ignored;
            std::filesystem::remove_all(path_, ignored);
        }
    }
    WorkDir(const WorkDir&) = delete;
    WorkDir& operator=(const WorkDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
    bool owned_ = false;
};

}  // namespace

nlohmann::json stress_script_header(const StressOptions& options) {
    return {{"version", 1},
            {"terrain",
             {{"size", {1.0, 1.0}},
              {"points", options.terrain_points},
              {"seed", options.seed},
              {"height", 0.1}}},
            {"settings",
             {{"keep_generations", 16},
              {"simplify", true},
              {"simplify_tolerance", 0.0005},
              {"relocation_radius", 0.05}}}};
}

nlohmann::json StressReport::to_json() const {
    nlohmann::json j = {{"seed", seed},
                        {"operations", operations_run},
                        {"rejected", rejected},
                        {"op_counts", op_counts},
                        {"op_seconds", op_seconds},
                        {"vertex_trace", vertex_trace},
                        {"rejections", rejections},
                        {"seconds", seconds},
                        {"full_checks", full_checks},
                        {"max_vertices", max_vertices},
                        {"max_constraints", max_constraints},
                        {"final_vertices", final_vertices},
                        {"max_volume_residual", max_volume_residual},
                        {"ok", !failure.has_value()}};
    if (failure) {
        j["failure"] = {{"operation", failure->operation},
                        {"invariant", failure->invariant},
                        {"detail", failure->detail},
                        {"script_operations", failure->script_operations},
                        {"script", failure->script}};
    }
    return j;
}

StressReport run_stress(const StressOptions& options,
                        const std::function<void(std::size_t)>& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const WorkDir dir(options.work_dir, options.seed);
    const nlohmann::json header = stress_script_header(options);
    StressReport report;
    report.seed = options.seed;
    StressSession session(header, dir.path(), options);
    RandomOperations generator(options.seed, session.tin().domain(), kSaveName);
    const std::size_t every = std::max<std::size_t>(options.full_check_every, 1);
    std::vector<nlohmann::json> ops;
    for (std::size_t k = 0; k < options.operations; ++k) {
        ops.push_back(generator.next(session.tin()));
        const std::string name = ops.back().value("op", "?");
        ++report.op_counts[name];
        const auto op_start = std::chrono::steady_clock::now();
        const bool last = k + 1 == options.operations;
        const TriangulationCheck depth =
            last || (k + 1) % every == 0 ? TriangulationCheck::full : TriangulationCheck::skip;
        StressSession::Outcome o = session.apply(ops.back(), depth);
        report.full_checks += o.fully_checked ? 1 : 0;
        report.op_seconds[name] +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - op_start).count();
        ++report.operations_run;
        const std::size_t sample_every = std::max<std::size_t>(options.operations / 20, 1);
        if ((k + 1) % sample_every == 0)
            report.vertex_trace.push_back(session.tin().vertex_count());
        report.max_vertices = std::max(report.max_vertices, session.tin().vertex_count());
        report.max_constraints = std::max(report.max_constraints, session.tin().constraint_count());
        report.max_volume_residual = std::max(report.max_volume_residual, o.volume_residual);
        if (o.rejection) {
            ++report.rejected;
            const std::string first_line = o.rejection->substr(0, o.rejection->find('\n'));
            // Drop the "stress:<line>: operation 1 (op)" prefix so equal messages group.
            const std::size_t colon = first_line.find("): ");
            ++report.rejections[colon == std::string::npos ? first_line
                                                           : first_line.substr(colon + 3)];
        }
        if (progress) progress(k + 1);
        if (!o.violation) continue;

        StressFailure failure;
        failure.operation = k + 1;
        failure.invariant = o.violation->invariant;
        failure.detail = o.violation->detail;
        std::vector<std::size_t> keep(ops.size());
        for (std::size_t i = 0; i < keep.size(); ++i)
            keep[i] = i;
        if (options.minimise) {
            const std::string wanted = failure.invariant;
            keep = minimise_failing_sequence(
                ops.size(),
                [&](const std::vector<std::size_t>& subset) {
                    std::vector<nlohmann::json> sub;
                    for (std::size_t i : subset)
                        sub.push_back(ops[i]);
                    const std::optional<Replay> r = replay(header, sub, dir.path(), options);
                    return r && r->violation.invariant == wanted;
                },
                std::chrono::milliseconds(static_cast<long long>(options.minimise_seconds * 1e3)));
        }
        nlohmann::json script = header;
        script["operations"] = nlohmann::json::array();
        for (std::size_t i : keep)
            script["operations"].push_back(ops[i]);
        failure.script_operations = keep.size();
        failure.script = std::move(script);
        report.failure = std::move(failure);
        break;
    }
    report.final_vertices = session.tin().vertex_count();
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

}  // namespace sandtin
