// Live haptic editing: the tool follows the device and the button strokes; a recorded normal
// stroke renders a continuous force; recordings replay into the same terrain, both from the
// deterministic lock-step driver and from the real loop thread; `sandtin run` replays them.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "haptics/live_session.hpp"
#include "haptics/recording_replay.hpp"
#include "haptics/simulated_device.hpp"
#include "io/session_file.hpp"
#include "test_support.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::haptics {
namespace {

std::shared_ptr<const Tool> circle_tool() {
    return std::make_shared<const Tool>(
        Tool::build(parse_tool_spec(test::circle_tool_json(), ".", "test tool")));
}

Trajectory stroke_on_test_terrain() {
    const Trajectory t = load_trajectory(SANDTIN_HAPTICS_ASSETS "/stroke.traj");
    EXPECT_GT(t.samples.size(), 1000u);
    return t;
}

TEST(LiveEditor, ToolFollowsTheDeviceAndOnlyThePressedPathIsStamped) {
    Tin tin = make_recording_terrain(test::test_terrain(), test::headless());
    SculptContext context(tin.domain());
    LiveEditor editor(tin, circle_tool(), context, {});
    const double volume = tin.volume();
    // Hovering and moving without the button: nothing changes.
    editor.apply({0, {0.3, 0.5, 0.04}, 0});
    editor.apply({1, {0.35, 0.5, 0.04}, 0});
    EXPECT_EQ(editor.placement().centre, (Vec2{0.35, 0.5}));
    EXPECT_EQ(editor.placement().bottom, 0.04);
    EXPECT_EQ(tin.volume(), volume);
    // Button held above the sand: the stroke samples are skipped.
    EditResult r = editor.apply({2, {0.36, 0.5, 0.06}, kMainButton});
    r = editor.apply({3, {0.40, 0.5, 0.06}, kMainButton});
    EXPECT_EQ(r.stamps, 0u);
    EXPECT_GT(r.skipped, 0u);
    editor.apply({4, {0.40, 0.5, 0.06}, 0});
    EXPECT_EQ(tin.volume(), volume);
    // Pressed 4 mm into the sand and dragged 5 cm: a stamp every 5 mm, sand removed.
    editor.apply({5, {0.5, 0.5, 0.046}, kMainButton});
    r = editor.apply({6, {0.55, 0.5, 0.046}, kMainButton});
    EXPECT_GE(r.stamps, 10u);
    EXPECT_LT(r.volume_change, 0.0);
    EXPECT_TRUE(editor.stroking());
    editor.apply({7, {0.55, 0.5, 0.06}, 0});
    EXPECT_FALSE(editor.stroking());
    EXPECT_LT(tin.volume(), volume);
    const std::optional<double> h = tin.height_at({0.52, 0.5});
    ASSERT_TRUE(h.has_value());
    EXPECT_NEAR(*h, 0.046, 1e-9);  // dug to the tool's bottom
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

TEST(LiveEditor, SnapshotFollowsTheTool) {
    Tin tin = make_recording_terrain(test::test_terrain(), test::headless());
    SculptContext context(tin.domain());
    LiveEditor editor(tin, circle_tool(), context, {});
    editor.apply({0, {0.25, 0.75, 0.06}, 0});
    const HapticSnapshot s = editor.snapshot();
    EXPECT_EQ(s.centre, (Vec2{0.25, 0.75}));
    EXPECT_NEAR(s.centre_height, 0.05, 1e-12);
    EXPECT_GE(s.control_count, 12u);
}

TEST(HapticContinuity, RecordedNormalStrokeNeverJumpsMoreThanHalfANewton) {
    Tin tin = make_recording_terrain(test::test_terrain(), test::headless());
    SculptContext context(tin.domain());
    LiveEditor editor(tin, circle_tool(), context, {});
    const Trajectory stroke = stroke_on_test_terrain();
    // A 60 Hz simulation (every 16 ticks) and a fast one (every 2 ticks).
    for (std::uint32_t every : {16u, 2u}) {
        Tin t = make_recording_terrain(test::test_terrain(), test::headless());
        SculptContext c(t.domain());
        LiveEditor e(t, circle_tool(), c, {});
        const LockstepResult r = run_lockstep(e, stroke, {}, every);
        EXPECT_GT(r.stamps, 40u) << every;
        EXPECT_GT(r.max_force, 3.0) << every;  // the stroke is felt
        EXPECT_LE(r.max_force, 10.0) << every;
        EXPECT_LE(r.max_force_jump, 0.5) << every;
        // Zero force while hovering above the sand at the start.
        EXPECT_EQ(r.ticks.front().force, (Vec3{})) << every;
        EXPECT_EQ(r.ticks.back().force, (Vec3{})) << every;
    }
}

TEST(HapticRecording, LockstepRecordingRoundTripsAndReplaysIntoTheSameTerrain) {
    const ScriptTerrain terrain = test::test_terrain();
    Tin live = make_recording_terrain(terrain, test::headless());
    SculptContext context(live.domain());
    const TerrainSummary start = summarise(live);
    LiveEditSettings settings;
    settings.erode_iterations = 2;
    settings.physics.relocation_radius = 0.01;
    LiveEditor editor(live, circle_tool(), context, settings);
    const LockstepResult r = run_lockstep(editor, stroke_on_test_terrain(), {}, 16);
    const HapticRecording rec = make_recording(1000.0, test::circle_tool_json(), settings, terrain,
                                               1, start, r.ticks, r.edits, live);
    const HapticRecording back = parse_recording(format_recording(rec), "rec");
    EXPECT_EQ(back.ticks, rec.ticks);
    EXPECT_EQ(back.edits, rec.edits);
    EXPECT_EQ(back.result, rec.result);
    EXPECT_EQ(back.edit.erode_iterations, 2);
    EXPECT_EQ(back.edit.physics.relocation_radius, 0.01);
    ASSERT_TRUE(back.terrain.has_value());

    Tin replayed = make_recording_terrain(*back.terrain, test::headless());
    SculptContext replay_context(replayed.domain());
    const nlohmann::json report = replay_recording(back, replayed, replay_context, ".");
    EXPECT_EQ(report["stamps_applied"].get<std::size_t>(), r.stamps);
    EXPECT_TRUE(report["result_matches_recording"].get<bool>());
    EXPECT_FALSE(report.contains("warning")) << report.dump();
    test::expect_same_terrain(live, replayed);
    // A recording whose result the replay does not reproduce still replays, with a warning
    // that gives both results.
    HapticRecording altered = back;
    altered.result->vertices += 1;
    Tin again = make_recording_terrain(*back.terrain, test::headless());
    SculptContext again_context(again.domain());
    const nlohmann::json mismatch = replay_recording(altered, again, again_context, ".");
    EXPECT_FALSE(mismatch["result_matches_recording"].get<bool>());
    const std::string w = mismatch.value("warning", std::string());
    EXPECT_NE(w.find("does not reproduce the recording"), std::string::npos) << w;
    EXPECT_NE(w.find(std::to_string(altered.result->vertices) + " and"), std::string::npos) << w;
    // Replaying onto another terrain is refused.
    Tin other = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.02);
    SculptContext other_context(other.domain());
    EXPECT_THROW(replay_recording(back, other, other_context, "."), std::runtime_error);
}

TEST(HapticRecording, ThreadedSessionReplaysIntoTheSameTerrain) {
    const ScriptTerrain terrain = test::test_terrain();
    Tin live = make_recording_terrain(terrain, test::headless());
    SculptContext context(live.domain());
    const TerrainSummary start = summarise(live);
    LiveEditor editor(live, circle_tool(), context, {});
    const Trajectory stroke = stroke_on_test_terrain();
    SimulatedDevice device = SimulatedDevice::replay(stroke);
    ForceLoopConfig config;
    config.record_capacity = stroke.samples.size();
    config.try_realtime = false;
    ForceLoop loop(device, config);
    LiveSession session(editor, loop);
    loop.start();
    while (loop.running()) {
        session.step();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    session.step();  // the last tick, if the loop ended before we saw it
    loop.stop();
    const ForceLoopReport report = loop.report();
    EXPECT_TRUE(report.device_lost);
    EXPECT_EQ(loop.records().size(), stroke.samples.size());
    EXPECT_GT(session.steps(), 10u);
    EXPECT_GT(editor.total_stamps(), 20u);
    // Continuity on the real thread too (whatever the simulation's timing was).
    EXPECT_LE(report.max_force_jump, 0.5);
    EXPECT_LE(report.max_force, 10.0);

    const HapticRecording rec = make_recording(1000.0, test::circle_tool_json(), {}, terrain, 1,
                                               start, loop.records(), session.edits(), live);
    EXPECT_EQ(rec.ticks.size(), stroke.samples.size());
    Tin replayed = make_recording_terrain(terrain, test::headless());
    SculptContext replay_context(replayed.domain());
    replay_recording(parse_recording(format_recording(rec), "rec"), replayed, replay_context, ".");
    test::expect_same_terrain(live, replayed);
}

TEST(HapticRecording, TheCommittedSampleRecordingReplays) {
    // Whether it still reproduces the recorded result depends on the tools' code at the time;
    // here only that it loads, replays onto its terrain, digs and leaves a valid TIN.
    const HapticRecording rec = load_recording(SANDTIN_HAPTICS_ASSETS "/stroke.haptic.json");
    ASSERT_TRUE(rec.terrain.has_value());
    EXPECT_GT(rec.ticks.size(), 4000u);
    Tin tin = make_recording_terrain(*rec.terrain, test::headless());
    SculptContext context(tin.domain());
    const nlohmann::json report = replay_recording(rec, tin, context, SANDTIN_HAPTICS_ASSETS);
    EXPECT_GT(report["stamps_applied"].get<int>(), 40);
    EXPECT_LT(report["volume_change"].get<double>(), 0.0);
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

TEST(HapticRecording, BadRecordingsAreRejectedWithTheField) {
    const auto error_of = [](const std::string& text) -> std::string {
        try {
            parse_recording(text, "r.json");
        } catch (const std::exception& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(error_of("{").find("not valid JSON"), std::string::npos);
    EXPECT_NE(error_of("[]").find("must be a JSON object"), std::string::npos);
    EXPECT_NE(error_of(R"({"format": "x"})").find("\"format\""), std::string::npos);
    HapticRecording good;
    good.tool = test::circle_tool_json();
    nlohmann::json j = recording_to_json(good);
    EXPECT_EQ(error_of(j.dump()), "");
    nlohmann::json k = j;
    k["version"] = 2;
    EXPECT_NE(error_of(k.dump()).find("unsupported recording version 2"), std::string::npos);
    k = j;
    k["edit"]["spacing"] = -1;
    EXPECT_NE(error_of(k.dump()).find("spacing"), std::string::npos);
    k = j;
    k["edits"] = {{1, 2, 3}};
    EXPECT_NE(error_of(k.dump()).find("edits[0] must be an array of 5"), std::string::npos);
    k = j;
    k["ticks"] = {{0, 0, 0, -1, 0, 0, 0}};
    EXPECT_NE(error_of(k.dump()).find("ticks[0]"), std::string::npos);
    k = j;
    k.erase("start");
    EXPECT_NE(error_of(k.dump()).find("missing field \"start\""), std::string::npos);
    // A spacing that would stamp for days is refused before anything runs: two pressed edits
    // 0.8 m apart at 1e-12 m ask for 8e11 stamps. Released, the same path stamps nothing.
    k = j;
    k["edit"]["spacing"] = 1e-12;
    k["edit"]["button_mask"] = 1;
    k["edits"] = {{0, 0.1, 0.5, 0.04, 1}, {1, 0.9, 0.5, 0.04, 1}};
    const std::string too_many = error_of(k.dump());
    EXPECT_NE(too_many.find("spacing"), std::string::npos) << too_many;
    EXPECT_NE(too_many.find("8e+11 stamps"), std::string::npos) << too_many;
    k["edits"] = {{0, 0.1, 0.5, 0.04, 0}, {1, 0.9, 0.5, 0.04, 0}};
    EXPECT_EQ(error_of(k.dump()), "");
    // The bound itself: 0.8 m at 8e-7 m is a million stamps, allowed; a little less spacing
    // is not.
    k["edits"] = {{0, 0.1, 0.5, 0.04, 1}, {1, 0.9, 0.5, 0.04, 1}};
    k["edit"]["spacing"] = 8.0000001e-7;
    EXPECT_EQ(error_of(k.dump()), "");
    k["edit"]["spacing"] = 7.9e-7;
    EXPECT_NE(error_of(k.dump()).find("a replay may place"), std::string::npos);
    // An unknown field, at the top or inside an object, is an error, as in scripts.
    k = j;
    k["bogus"] = 1;
    EXPECT_NE(error_of(k.dump()).find("unknown field \"bogus\""), std::string::npos);
    k = j;
    k["edit"]["spacnig"] = 0.01;
    EXPECT_NE(error_of(k.dump()).find("edit: unknown field \"spacnig\""), std::string::npos);
    // A pen height beyond the 1e9 m a terrain may reach.
    k = j;
    k["edits"] = {{0, 0.5, 0.5, -1e300, 1}};
    EXPECT_NE(error_of(k.dump()).find("edits[0] has a height beyond"), std::string::npos);
    // Edits in the order they were taken: the same tick twice is fine, an earlier one is not.
    k = j;
    k["edits"] = {{3, 0.5, 0.5, 0.04, 0}, {3, 0.5, 0.5, 0.04, 0}, {7, 0.5, 0.5, 0.04, 0}};
    EXPECT_EQ(error_of(k.dump()), "");
    k["edits"] = {{3, 0.5, 0.5, 0.04, 0}, {7, 0.5, 0.5, 0.04, 0}, {5, 0.5, 0.5, 0.04, 0}};
    EXPECT_NE(error_of(k.dump()).find("edits[2] was taken at tick 5, before edits[1] (tick 7)"),
              std::string::npos)
        << error_of(k.dump());
    // The line of a JSON error, as in scripts.
    EXPECT_NE(error_of("{\n\"format\": 1e400}").find("r.json:2: not valid JSON"),
              std::string::npos);
    EXPECT_TRUE(is_haptic_recording(j.dump()));
    EXPECT_FALSE(is_haptic_recording(R"({"operations": []})"));
    EXPECT_FALSE(is_haptic_recording("not json"));
}

TEST(HapticRecording, SandtinRunReplaysARecording) {
    const std::filesystem::path dir = test::scratch_dir("run");
    const ScriptTerrain terrain = test::test_terrain();
    Tin live = make_recording_terrain(terrain, test::headless());
    SculptContext context(live.domain());
    const TerrainSummary start = summarise(live);
    LiveEditor editor(live, circle_tool(), context, {});
    const LockstepResult r = run_lockstep(editor, stroke_on_test_terrain(), {}, 16);
    save_recording(dir / "stroke.haptic.json",
                   make_recording(1000.0, test::circle_tool_json(), {}, terrain, 1, start, r.ticks,
                                  r.edits, live));
    const int rc = test::run_process({SANDTIN_CLI, "run", (dir / "stroke.haptic.json").string(),
                                      "-o", (dir / "out.sandtin").string(), "--json"},
                                     dir / "out.txt", dir / "err.txt");
    ASSERT_EQ(rc, 0) << test::read_text(dir / "err.txt");
    const nlohmann::json out = nlohmann::json::parse(test::read_text(dir / "out.txt"));
    EXPECT_TRUE(out["steps"][0]["result_matches_recording"].get<bool>());
    const Session session = load_session(dir / "out.sandtin");
    test::expect_same_terrain(live, Tin::from_snapshot(session.terrain));

    // A broken recording: a clear error, non-zero exit, no output file.
    {
        std::ofstream bad(dir / "bad.haptic.json");
        bad << R"({"format": "sandtin-haptic-recording", "version": 1, "rate_hz": 1000})";
    }
    const int bad_rc = test::run_process({SANDTIN_CLI, "run", (dir / "bad.haptic.json").string(),
                                          "-o", (dir / "bad.sandtin").string()},
                                         dir / "bad-out.txt", dir / "bad-err.txt");
    EXPECT_NE(bad_rc, 0);
    EXPECT_NE(test::read_text(dir / "bad-err.txt").find("missing field \"tool\""),
              std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.sandtin"));
}

}  // namespace
}  // namespace sandtin::haptics
