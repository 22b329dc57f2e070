// The stress runner itself: short sessions keep every invariant, an injected bound violation is
// found, minimised and reproduced by the script it prints, and ddmin finds minimal failing
// subsets of synthetic predicates (oracle: the subset is known by construction).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>
#include <vector>

#include "io/script.hpp"
#include "stress/minimise_failing_sequence.hpp"
#include "stress/stress_runner.hpp"
#include "stress/terrain_invariants.hpp"
#include "tools/sculpt_context.hpp"

namespace sandtin {
namespace {

std::filesystem::path scratch_dir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("sandtin-stress-test-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// ---- ddmin ----------------------------------------------------------------------------------

TEST(MinimiseFailingSequence, FindsTheSingleCulprit) {
    int calls = 0;
    const auto kept = minimise_failing_sequence(100, [&](const std::vector<std::size_t>& s) {
        ++calls;
        return std::find(s.begin(), s.end(), 37u) != s.end();
    });
    EXPECT_EQ(kept, std::vector<std::size_t>{37});
    EXPECT_LT(calls, 200);
}

TEST(MinimiseFailingSequence, FindsAPairThatOnlyFailsTogetherInOrder) {
    // Fails when 12 comes before 80 in the subsequence (indices stay increasing).
    const auto kept = minimise_failing_sequence(120, [](const std::vector<std::size_t>& s) {
        const auto a = std::find(s.begin(), s.end(), 12u);
        const auto b = std::find(s.begin(), s.end(), 80u);
        return a != s.end() && b != s.end() && a < b;
    });
    EXPECT_EQ(kept, (std::vector<std::size_t>{12, 80}));
}

TEST(MinimiseFailingSequence, ResultIsOneMinimalForAThresholdPredicate) {
    // Fails when at least 3 of the multiples of 7 are present: any 3 of them is 1-minimal.
    const auto kept = minimise_failing_sequence(70, [](const std::vector<std::size_t>& s) {
        return std::count_if(s.begin(), s.end(), [](std::size_t i) { return i % 7 == 0; }) >= 3;
    });
    ASSERT_EQ(kept.size(), 3u);
    for (std::size_t i : kept)
        EXPECT_EQ(i % 7, 0u);
    EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
}

TEST(MinimiseFailingSequence, StopsWhenTheBudgetRunsOutAndStillReturnsAFailingSet) {
    std::set<std::size_t> needed = {3, 50, 99};
    const auto kept = minimise_failing_sequence(
        100,
        [&](const std::vector<std::size_t>& s) {
            return std::all_of(needed.begin(), needed.end(), [&](std::size_t k) {
                return std::find(s.begin(), s.end(), k) != s.end();
            });
        },
        std::chrono::nanoseconds(1));
    for (std::size_t k : needed)
        EXPECT_NE(std::find(kept.begin(), kept.end(), k), kept.end());
}

void constrain(Tin& tin, Vec2 a, Vec2 b, Generation generation) {
    const VertexId va = tin.insert_point_on_surface(a);
    const VertexId vb = tin.insert_point_on_surface(b);
    tin.insert_constraint(va, vb, generation);
}

// ---- invariants -----------------------------------------------------------------------------

TEST(TerrainInvariants, AFreshTerrainPasses) {
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 200, 3);
    EXPECT_FALSE(check_terrain_invariants(tin, 1, {}).has_value());
}

TEST(TerrainInvariants, ConstraintsFromGenerationsNotHandedOutAreReported) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.0);
    constrain(tin, {0.2, 0.2}, {0.8, 0.3}, 5);
    EXPECT_FALSE(check_terrain_invariants(tin, 6, {}).has_value());
    const auto v = check_terrain_invariants(tin, 5, {});
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->invariant, "generations");
    // Generation 0 is the terrain before the first stamp (whose fences guard it).
    Tin fenced = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.0);
    constrain(fenced, {0.2, 0.2}, {0.8, 0.3}, 0);
    EXPECT_FALSE(check_terrain_invariants(fenced, 1, {}).has_value());
}

TEST(TerrainInvariants, VertexAndConstraintBoundsAreReported) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 100, 4);
    auto v = check_terrain_invariants(tin, 1, {.max_vertices = 50, .max_constraints = 0});
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->invariant, "bounded");
    constrain(tin, {0.1, 0.1}, {0.9, 0.9}, 1);
    constrain(tin, {0.1, 0.9}, {0.9, 0.8}, 1);
    v = check_terrain_invariants(tin, 2, {.max_vertices = 0, .max_constraints = 1});
    ASSERT_TRUE(v.has_value());
    EXPECT_EQ(v->invariant, "bounded");
}

// ---- the runner -----------------------------------------------------------------------------

StressOptions short_session(std::uint64_t seed, std::size_t operations, std::size_t points,
                            const std::string& dir) {
    StressOptions options;
    options.seed = seed;
    options.operations = operations;
    options.terrain_points = points;
    options.work_dir = scratch_dir(dir);
    return options;
}

TEST(StressRunner, AShortSessionKeepsEveryInvariantAndConservesVolume) {
    StressOptions options = short_session(11, 150, 300, "short");
    const StressReport report = run_stress(options);
    ASSERT_FALSE(report.failure.has_value()) << report.to_json().dump(2);
    EXPECT_EQ(report.operations_run, 150u);
    // Every kind of operation ran (the generator's mix), and the degenerate tools were
    // rejected by the parser rather than crashing anything.
    for (const char* op : {"stamp", "stroke", "brush", "erode", "simplify"})
        EXPECT_GT(report.op_counts.count(op), 0u) << op;
    EXPECT_LE(report.max_volume_residual, 1e-9);
}

TEST(StressRunner, AnInjectedViolationIsMinimisedIntoAScriptThatReproducesIt) {
    StressOptions options = short_session(5, 200, 200, "inject");
    // A bound the first real stamp breaks: constraints are the rims stamps leave.
    options.limits = InvariantLimits{.max_vertices = 0, .max_constraints = 1};
    options.minimise_seconds = 60.0;
    const StressReport report = run_stress(options);
    ASSERT_TRUE(report.failure.has_value()) << report.to_json().dump(1);
    EXPECT_EQ(report.failure->invariant, "bounded");
    // Minimal: one operation that leaves two constraints is enough, but ddmin may keep a few.
    EXPECT_GE(report.failure->script_operations, 1u);
    EXPECT_LT(report.failure->script_operations, report.failure->operation);

    // The printed script is a valid `sandtin run` script, and replaying it breaks the bound.
    const nlohmann::json& script_json = report.failure->script;
    const Script script = parse_script(script_json.dump(), "repro", options.work_dir);
    Tin tin = make_script_terrain(*script.terrain);
    SculptContext context(tin.domain());
    ScriptRunner runner(script, tin, context, true);
    for (const ScriptStep& step : script.steps)
        runner.run(step);
    EXPECT_GT(tin.constraint_count(), 1u);
}

TEST(StressRunner, TheFullTriangulationCheckRunsEveryKthOperationEverySaveAndAfterTheLast) {
    StressOptions options = short_session(13, 30, 200, "every-1");
    const StressReport every_one = run_stress(options);
    ASSERT_FALSE(every_one.failure.has_value()) << every_one.to_json().dump(1);
    EXPECT_EQ(every_one.full_checks, 30u);

    options.work_dir = scratch_dir("every-7");
    options.full_check_every = 7;
    const StressReport every_seven = run_stress(options);
    ASSERT_FALSE(every_seven.failure.has_value()) << every_seven.to_json().dump(1);
    // After operations 7, 14, 21, 28 and 30, and after each save (which may coincide).
    const std::size_t saves =
        every_seven.op_counts.count("save") ? every_seven.op_counts.at("save") : 0;
    EXPECT_GE(every_seven.full_checks, 5u);
    EXPECT_LE(every_seven.full_checks, 5u + saves);
    // Checking less does not change what the session does.
    EXPECT_EQ(every_seven.vertex_trace, every_one.vertex_trace);
    EXPECT_EQ(every_seven.final_vertices, every_one.final_vertices);
}

TEST(StressRunner, TheOtherInvariantsAreCheckedAfterEveryOperationWhateverTheStride) {
    // The bound breaks at the first operation that leaves two constraints; a session that
    // checks the triangulation only every 1000th operation must stop at the same one.
    StressOptions options = short_session(5, 200, 200, "stride-1");
    options.limits = InvariantLimits{.max_vertices = 0, .max_constraints = 1};
    options.minimise = false;
    const StressReport strict = run_stress(options);
    options.work_dir = scratch_dir("stride-1000");
    options.full_check_every = 1000;
    const StressReport strided = run_stress(options);
    ASSERT_TRUE(strict.failure.has_value());
    ASSERT_TRUE(strided.failure.has_value());
    EXPECT_EQ(strided.failure->invariant, "bounded");
    EXPECT_EQ(strided.failure->operation, strict.failure->operation);
    EXPECT_LT(strided.full_checks, strict.full_checks);
}

TEST(StressRunner, TheSameSeedGivesTheSameSession) {
    StressOptions options = short_session(21, 60, 200, "same-a");
    const StressReport a = run_stress(options);
    options.work_dir = scratch_dir("same-b");
    const StressReport b = run_stress(options);
    ASSERT_FALSE(a.failure.has_value());
    EXPECT_EQ(a.op_counts, b.op_counts);
    EXPECT_EQ(a.vertex_trace, b.vertex_trace);
    EXPECT_EQ(a.final_vertices, b.final_vertices);
    EXPECT_EQ(a.max_constraints, b.max_constraints);
}

}  // namespace
}  // namespace sandtin
