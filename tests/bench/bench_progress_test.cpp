// The benchmark drivers' progress reports (BenchConfig::progress) keep the contract of
// engine/io/progress.hpp: fractions in [0, 1] that never fall and end at exactly 1, a stage for
// each part measured, and the same measurements with or without a listener. Quick mode, so the
// drivers run in seconds; no timing is asserted.

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "bench_groove.hpp"
#include "bench_import.hpp"
#include "bench_tin.hpp"

namespace sandtin::bench {
namespace {

struct Recorded {
    std::vector<double> fractions;
    std::vector<std::string> stages;
};

BenchConfig recording(Recorded& r) {
    BenchConfig config;
    config.quick = true;
    config.progress = [&r](const Progress& p) {
        r.fractions.push_back(p.fraction);
        r.stages.emplace_back(p.stage);
    };
    return config;
}

void expect_contract(const Recorded& r, std::size_t min_stages) {
    ASSERT_FALSE(r.fractions.empty());
    for (std::size_t i = 0; i < r.fractions.size(); ++i) {
        EXPECT_GE(r.fractions[i], 0.0) << i;
        EXPECT_LE(r.fractions[i], 1.0) << i;
        if (i > 0) {
            EXPECT_GE(r.fractions[i], r.fractions[i - 1]) << r.stages[i];
        }
    }
    EXPECT_EQ(r.fractions.back(), 1.0);
    // Exactly one report of 1: the end.
    for (std::size_t i = 0; i + 1 < r.fractions.size(); ++i)
        EXPECT_LT(r.fractions[i], 1.0) << r.stages[i];
    const std::set<std::string> distinct(r.stages.begin(), r.stages.end());
    EXPECT_GE(distinct.size(), min_stages);
    EXPECT_LE(r.fractions.size(), 300u);  // a few hundred calls at most
}

bool any_stage_contains(const Recorded& r, const std::string& text) {
    for (const std::string& s : r.stages)
        if (s.find(text) != std::string::npos) return true;
    return false;
}

TEST(BenchProgress, TinReportsEachPartInOrderAndMeasuresTheSame) {
    Recorded r;
    const nlohmann::json with = bench_tin(recording(r));
    // Quick: 2 sizes x 2 insertion runs, location, removal, rings, 1 restore, done.
    expect_contract(r, 9);
    for (const char* part : {"inserting", "point location", "vertex removal", "rings", "restoring"})
        EXPECT_TRUE(any_stage_contains(r, part)) << part;
    BenchConfig silent;
    silent.quick = true;
    const nlohmann::json without = bench_tin(silent);
    // Everything that is not a time is the same with and without a listener.
    EXPECT_EQ(with["constraints"]["vertices_after"], without["constraints"]["vertices_after"]);
    EXPECT_EQ(with["constraints"]["constrained_edges_after"],
              without["constraints"]["constrained_edges_after"]);
    EXPECT_EQ(with["remove"]["removed"], without["remove"]["removed"]);
    // (Not locate's checksum: CGAL's stochastic walk draws from a process-wide generator.)
}

TEST(BenchProgress, GrooveReportsSizesLocalityAndTraces) {
    Recorded r;
    const nlohmann::json j = bench_groove(recording(r));
    // Quick: 2 sizes (a run, erosion, rest each), 2 locality parts, 8 trace lengths, done.
    expect_contract(r, 17);
    EXPECT_TRUE(any_stage_contains(r, "with erosion"));
    EXPECT_TRUE(any_stage_contains(r, "eroded to rest"));
    EXPECT_TRUE(any_stage_contains(r, "locality"));
    EXPECT_TRUE(any_stage_contains(r, "trace length 8 of 8"));
    EXPECT_EQ(j["by_trace"].size(), 8u);
    // The groove to rest under the physics' default (the face rule, issue 39) and, side by
    // side, the edge rule at the same margin and the seeds' rule (the edge rule, no margin):
    // each rests, and each moved sand to get there.
    const nlohmann::json& rest = j.at("by_size").at(0).at("to_rest");
    const nlohmann::json& edge = rest.at("edge_rule");
    const nlohmann::json& seeds = rest.at("seeds_rule");
    for (const nlohmann::json* run : {&rest, &edge, &seeds}) {
        EXPECT_TRUE(run->at("at_rest").get<bool>()) << run->dump();
        EXPECT_GT(run->at("vertex_updates").get<std::size_t>(), 0u) << run->dump();
    }
    EXPECT_EQ(rest.at("rule"), "face");
    EXPECT_EQ(edge.at("rule"), "edge");
    EXPECT_EQ(seeds.at("rule"), "edge");
    EXPECT_EQ(edge.at("settle_margin"), rest.at("settle_margin"));
    EXPECT_GT(rest.at("settle_margin").get<double>(), 0.0);
    EXPECT_EQ(seeds.at("settle_margin").get<double>(), 0.0);
}

TEST(BenchProgress, ImportReportsEachErrorLevelAndDelatin) {
    Recorded r;
    const nlohmann::json j = bench_import(recording(r));
    // Quick: one run at each of bay-hills' 3 errors and delatin (run or found missing), then
    // the same on the rough 256² tile at 10 m, done.
    expect_contract(r, 6);
    EXPECT_TRUE(any_stage_contains(r, "sandtin on bay-hills to 0.2 m"));
    EXPECT_TRUE(any_stage_contains(r, "delatin on bay-hills"));
    EXPECT_TRUE(any_stage_contains(r, "sandtin on fbm-256 to 10 m"));
    EXPECT_TRUE(any_stage_contains(r, "delatin on fbm-256"));
    EXPECT_EQ(j["sandtin"].size(), 3u);
    ASSERT_EQ(j["rough_tiles"].size(), 1u);
    EXPECT_EQ(j["rough_tiles"][0]["sandtin"].size(), 1u);
}

}  // namespace
}  // namespace sandtin::bench
