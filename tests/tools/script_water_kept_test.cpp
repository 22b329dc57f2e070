// Water kept between operations (io/script_water.hpp): what one water operation leaves on the
// terrain, the next starts from, with the volume carried over to rounding (a conservation law:
// walls all round and no evaporation, so the water at the end of "rain" is the water at the
// start and end of "flow"); "flow" until rest stops before its seconds run out, and a second
// one on water at rest stops after its first step; "flow" until dry with evaporation leaves no
// water and accounts for all of it; "rain" and "flow" name their bad fields.

#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "io/script.hpp"
#include "support/tin_oracles.hpp"
#include "tin/vertex_arrays.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {
namespace script_water_kept_test {

Script parse(const std::string& text) {
    return parse_script(text, "kept.json", ".");
}

std::string error_of(const std::string& op) {
    try {
        parse("[" + op + "]");
    } catch (const JsonInputError& e) {
        return e.what();
    }
    return "";
}

/// A flat terrain 1 m square: rain on a disc spreads out from it.
constexpr const char* kFlat = R"("terrain": {"size": [1, 1], "points": 1500, "seed": 9,
                                             "height": 0.1})";

TEST(ScriptWaterKept, TheWaterOneOperationLeavesTheNextStartsFrom) {
    for (const char* scheme : {"pipes", "shallow_water"}) {
        SCOPED_TRACE(scheme);
        const Script s = parse(std::string(R"({"version": 1, )") + kFlat + R"(,
            "operations": [
              {"op": "rain", "seconds": 1, "mm_per_hour": 3600, "centre": [0.5, 0.5],
               "radius": 0.2, "scheme": ")" +
                               scheme + R"("},
              {"op": "flow", "seconds": 1, "scheme": ")" +
                               scheme + R"("}]})");
        Tin tin = make_script_terrain(*s.terrain);
        SculptContext context(tin.domain());
        const nlohmann::json reports = run_script(s, tin, context);
        const double rained = reports.at(0).at("water_m3").get<double>();
        ASSERT_GT(rained, 0.0);
        EXPECT_NEAR(reports.at(0).at("added_m3").get<double>(), rained, 1e-12 * rained);
        EXPECT_EQ(reports.at(0).at("water_at_start_m3").get<double>(), 0.0);
        const nlohmann::json& flow = reports.at(1);
        EXPECT_NEAR(flow.at("water_at_start_m3").get<double>(), rained, 1e-12 * rained);
        EXPECT_EQ(flow.at("added_m3").get<double>(), 0.0);
        EXPECT_NEAR(flow.at("water_m3").get<double>(), rained, 1e-12 * rained);
        EXPECT_EQ(flow.at("stopped").get<std::string>(), "seconds");
        EXPECT_NEAR(flow.at("seconds").get<double>(), 1.0, 1e-12);
        // And the terrain holds it at the end.
        EXPECT_NEAR(test::water_volume(tin), rained, 1e-12 * rained);
        EXPECT_TRUE(tin.check_valid().ok());
    }
}

TEST(ScriptWaterKept, FlowUntilRestStopsWhenTheWaterStands) {
    const Script s = parse(std::string(R"({"version": 1, )") + kFlat + R"(,
        "operations": [
          {"op": "rain", "seconds": 0.5, "mm_per_hour": 7200, "centre": [0.3, 0.3],
           "radius": 0.1},
          {"op": "flow", "until": "rest", "seconds": 600, "rest_rate": 1e-5},
          {"op": "flow", "until": "rest", "seconds": 600, "rest_rate": 1e-5}]})");
    Tin tin = make_script_terrain(*s.terrain);
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const nlohmann::json& settle = reports.at(1);
    EXPECT_EQ(settle.at("stopped").get<std::string>(), "rest");
    EXPECT_LT(settle.at("seconds").get<double>(), 600.0);
    EXPECT_GT(settle.at("steps").get<std::size_t>(), 1u);
    // Water that stands stays standing: the next flow until rest takes one step.
    const nlohmann::json& again = reports.at(2);
    EXPECT_EQ(again.at("stopped").get<std::string>(), "rest");
    EXPECT_EQ(again.at("steps").get<std::size_t>(), 1u);
    const double water = reports.at(0).at("water_m3").get<double>();
    EXPECT_NEAR(again.at("water_m3").get<double>(), water, 1e-12 * water);
}

TEST(ScriptWaterKept, FlowUntilDryLeavesNoWaterAndAccountsForAllOfIt) {
    const Script s = parse(std::string(R"({"version": 1, )") + kFlat + R"(,
        "operations": [
          {"op": "rain", "seconds": 1, "mm_per_hour": 360},
          {"op": "flow", "until": "dry", "seconds": 3600, "evaporation_mm_per_hour": 3600,
           "open_sides": ["east"]}]})");
    Tin tin = make_script_terrain(*s.terrain);
    SculptContext context(tin.domain());
    const nlohmann::json reports = run_script(s, tin, context);
    const nlohmann::json& flow = reports.at(1);
    EXPECT_EQ(flow.at("stopped").get<std::string>(), "dry");
    EXPECT_LT(flow.at("seconds").get<double>(), 3600.0);
    EXPECT_EQ(flow.at("water_m3").get<double>(), 0.0);
    EXPECT_EQ(test::water_volume(tin), 0.0);
    const double start = flow.at("water_at_start_m3").get<double>();
    ASSERT_GT(start, 0.0);
    const double gone = flow.at("evaporated_m3").get<double>() + flow.at("left_m3").get<double>();
    EXPECT_NEAR(gone, start, 1e-12 * start);
}

TEST(ScriptWaterKept, RainAndFlowNameTheirBadFields) {
    const std::pair<const char*, const char*> bad[] = {
        {R"({"op": "rain", "seconds": 1})", "mm_per_hour"},
        {R"({"op": "rain", "seconds": 1, "mm_per_hour": 0})", "mm_per_hour"},
        {R"({"op": "rain", "seconds": 1, "mm_per_hour": 5, "radius": 0.1})", "centre"},
        {R"({"op": "rain", "seconds": 1, "mm_per_hour": 5, "rain": {"mm_per_hour": 5}})", "rain"},
        {R"({"op": "flow", "seconds": 1, "rain": {"mm_per_hour": 5}})", "rain"},
        {R"({"op": "flow", "seconds": 1, "nozzles": []})", "nozzles"},
        {R"({"op": "flow"})", "seconds"},
        {R"({"op": "flow", "seconds": 1, "until": "wet"})", "until"},
        {R"({"op": "flow", "seconds": 1, "rest_rate": 1e-5})", "rest_rate"},
        {R"({"op": "flow", "seconds": 1, "until": "rest", "rest_depth": 1e-5})", "rest_depth"},
        {R"({"op": "flow", "seconds": 1, "until": "rest", "rest_rate": -1})", "rest_rate"},
        {R"({"op": "water", "seconds": 1})", "source"}};
    for (const auto& [text, field] : bad) {
        const std::string what = error_of(text);
        EXPECT_NE(what.find(field), std::string::npos) << text << ": " << what;
    }
    const Script good = parse(R"([{"op": "flow", "seconds": 5, "until": "dry", "rest_depth": 1e-4,
                                   "evaporation_mm_per_hour": 2}])");
    const WaterOp& op = std::get<WaterOp>(good.steps.at(0).operation);
    EXPECT_EQ(op.until, WaterStop::Dry);
    EXPECT_EQ(op.rest_depth, 1e-4);
    EXPECT_TRUE(op.sources.rain.empty());
    EXPECT_TRUE(op.sources.nozzles.empty());
}

}  // namespace script_water_kept_test
}  // namespace
}  // namespace sandtin
