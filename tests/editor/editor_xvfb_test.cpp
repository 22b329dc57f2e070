// The editor binary under Xvfb on whatever Vulkan device exists (lavapipe in CI), driven by
// scripts through the real input path, with the validation layer on: every run must exit 0
// with no validation message. Oracles are independent of the renderer's code: pixel
// statistics of the screenshots, the script's own mouse positions, and the saved session read
// back through engine/io.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"
#include "editor_settings.hpp"
#include "formats/png_image.hpp"
#include "frame_policy.hpp"
#include "io/autosave.hpp"
#include "io/scene_materials.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "physics/physics_oracles.hpp"
#include "physics/sand_physics.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"
#include "tool_palette.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

TEST_F(EditorXvfb, ScreenshotShowsLitTexturedTerrainAndThePanel) {
    const fs::path shot = kWork / "flat.png";
    const EditorRun r = run_editor("flat", kFlat, "--frames 2 --screenshot " + shot.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const PngImage im = read_png(shot);
    ASSERT_EQ(im.width, 1280u);
    ASSERT_EQ(im.height, 720u);
    // Terrain: the centre of the view. Lit and textured = many distinct shades, not one colour,
    // and warm (sand: red > blue).
    double sum = 0, sum2 = 0, red = 0, blue = 0;
    int n = 0;
    for (std::uint32_t y = 300; y < 500; ++y) {
        for (std::uint32_t x = 600; x < 900; ++x) {
            const Rgb c = pixel(im, x, y);
            const double l = luminance(c);
            sum += l;
            sum2 += l * l;
            red += c.r;
            blue += c.b;
            ++n;
        }
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_GT(mean, 60.0);
    EXPECT_GT(sd, 3.0) << "terrain looks like a flat colour";
    EXPECT_GT(red, blue * 1.1);
    // The panel: bright text on ImGui's neutral grey window background, which the bluish
    // clear colour around the terrain is not.
    auto panel_grey = [](Rgb c) {
        return std::abs(c.r - c.b) <= 4 && luminance(c) > 40 && luminance(c) < 90;
    };
    EXPECT_FALSE(panel_grey(pixel(im, 1270, 710))) << "the test's colour oracle is ambiguous";
    int bright = 0, grey = 0;
    for (std::uint32_t y = 20; y < 700; ++y) {
        for (std::uint32_t x = 12; x < 290; ++x) {
            const Rgb c = pixel(im, x, y);
            bright += luminance(c) > 200 ? 1 : 0;
            grey += panel_grey(c) ? 1 : 0;
        }
    }
    EXPECT_GT(bright, 2000) << "no panel text";
    EXPECT_GT(grey, 30000) << "no panel background";
}

TEST_F(EditorXvfb, StrokeChangesPixelsWhereDrawnAndTheSavedSceneHoldsIt) {
    const fs::path flat_png = kWork / "flat2.png", stroke_png = kWork / "stroke.png";
    const fs::path flat_scene = kWork / "flat2.sandtin", stroke_scene = kWork / "stroke.sandtin";
    const EditorRun a = run_editor(
        "flat2", kFlat,
        "--frames 2 --screenshot " + flat_png.string() + " --save-after " + flat_scene.string());
    const EditorRun b = run_editor("stroke", kStroke,
                                   "--frames 2 --screenshot " + stroke_png.string() +
                                       " --save-after " + stroke_scene.string());
    ASSERT_EQ(a.exit_code, 0) << a.log;
    ASSERT_EQ(b.exit_code, 0) << b.log;
    EXPECT_EQ(b.stats.at("validation_messages").get<int>(), 0);
    const PngImage pa = read_png(flat_png), pb = read_png(stroke_png);
    // Along the stroke (y = 0.5 of the window, x from 0.45 to 0.75) the pixels changed...
    const double along = mean_diff(pa, pb, 600, 340, 940, 380);
    // ...and in terrain far from it (lower left of the terrain) they did not.
    const double away = mean_diff(pa, pb, 450, 560, 600, 620);
    EXPECT_GT(along, 4.0);
    EXPECT_LT(away, 0.5);
    EXPECT_GT(along, 10.0 * away + 1.0);

    // The saved scene holds the stroke: a groove of vertices at least 5 mm below the untouched
    // surface, stretched along the drag (which spans 30 % of the window's width).
    const Session s0 = load_session(flat_scene), s1 = load_session(stroke_scene);
    const Tin t0 = Tin::from_snapshot(s0.terrain), t1 = Tin::from_snapshot(s1.terrain);
    EXPECT_GT(s1.next_generation, s0.next_generation);
    std::size_t dug = 0;
    double lo = 1e9, hi = -1e9;
    const VertexArrays& v1 = t1.vertices();
    for (std::size_t i = 0; i < v1.size(); ++i) {
        if (!v1.alive[i]) continue;
        if (*t0.height_at(v1.position[i]) - v1.height[i] > 0.005) {
            ++dug;
            lo = std::min(lo, v1.position[i].x);
            hi = std::max(hi, v1.position[i].x);
        }
    }
    EXPECT_GT(dug, 50u);
    EXPECT_GT(hi - lo, 0.15) << "the groove is not stretched along the stroke";
    // The pour left a pile where the cursor (the pour point) is.
    const auto cur = b.stats.at("cursor");
    const Vec2 pour{cur[0].get<double>(), cur[1].get<double>()};
    EXPECT_GT(*t1.height_at(pour), *t0.height_at(pour) + 1e-3) << "the pour left no pile";
}

TEST_F(EditorXvfb, ToolCursorIsDrawnWhereTheMouseRayMeetsTheTerrain) {
    const fs::path shot = kWork / "cursor.png";
    const EditorRun r = run_editor("cursor",
                                   R"([{"op": "set", "erosion": false, "radius": 0.04},
                                 {"op": "tool", "name": "Circle"},
                                 {"op": "move", "at": [0.55, 0.55]}, {"op": "wait", "frames": 2}])",
                                   "--frames 1 --screenshot " + shot.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const PngImage im = read_png(shot);
    // The cursor ring is cyan (low red, high green and blue); its centre is the mouse pixel.
    double sx = 0, sy = 0;
    int n = 0;
    for (std::uint32_t y = 0; y < im.height; ++y) {
        for (std::uint32_t x = 320; x < im.width; ++x) {
            const Rgb c = pixel(im, x, y);
            if (c.r < 120 && c.g > 180 && c.b > 180) {
                sx += x;
                sy += y;
                ++n;
            }
        }
    }
    ASSERT_GT(n, 30) << "no cursor ring";
    EXPECT_NEAR(sx / n, 0.55 * 1280, 8.0);
    EXPECT_NEAR(sy / n, 0.55 * 720, 8.0);
}

TEST_F(EditorXvfb, UndoThroughTheKeyboardRestoresTheSavedScene) {
    const fs::path base = kWork / "undo-base.sandtin", undone = kWork / "undone.sandtin";
    const EditorRun a = run_editor("undo-base", kFlat, "--save-after " + base.string());
    const EditorRun b =
        run_editor("undo",
                   R"([{"op": "set", "erosion": false}, {"op": "tool", "name": "Circle"},
                                 {"op": "drag", "path": [[0.45, 0.5], [0.6, 0.47]], "steps": 20},
                                 {"op": "tool", "name": "Raise"},
                                 {"op": "drag", "path": [[0.6, 0.6], [0.65, 0.62]], "steps": 5},
                                 {"op": "key", "key": "z", "ctrl": true},
                                 {"op": "key", "key": "z", "ctrl": true},
                                 {"op": "key", "key": "y", "ctrl": true},
                                 {"op": "key", "key": "z", "ctrl": true}])",
                   "--save-after " + undone.string());
    ASSERT_EQ(a.exit_code, 0) << a.log;
    ASSERT_EQ(b.exit_code, 0) << b.log;
    const Tin t0 = Tin::from_snapshot(load_session(base).terrain);
    const Tin t1 = Tin::from_snapshot(load_session(undone).terrain);
    ASSERT_EQ(t0.vertex_count(), t1.vertex_count());
    EXPECT_EQ(t1.constrained_edge_count(), 0u);
    EXPECT_DOUBLE_EQ(t0.volume(), t1.volume());
    // Same vertices with the same heights (positions are exact; ids may differ).
    std::map<std::pair<double, double>, double> h0;
    const VertexArrays& v0 = t0.vertices();
    for (std::size_t i = 0; i < v0.size(); ++i) {
        if (v0.alive[i]) h0[{v0.position[i].x, v0.position[i].y}] = v0.height[i];
    }
    const VertexArrays& v1 = t1.vertices();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < v1.size(); ++i) {
        if (!v1.alive[i]) continue;
        const auto it = h0.find({v1.position[i].x, v1.position[i].y});
        if (it == h0.end() || it->second != v1.height[i]) ++differ;
    }
    EXPECT_EQ(differ, 0u);
}

TEST_F(EditorXvfb, HapticsPanelRunsTheForceLoopAgainstTheSandUnderTheCursor) {
    // The simulated pen follows the cursor with its tip the tool depth below the surface, so
    // it is in contact and pushed back up: a force in (0, max], and the loop ticks at ~1 kHz.
    // Then the editor sits idle for a second. The loop fades the force out 100-300 ms after
    // the newest snapshot, and a frame here takes about 170 ms (lavapipe, validation on), so
    // the force is still there at the end only if the snapshot was held fresh while the editor
    // drew and waited (haptics/snapshot_heartbeat.hpp).
    const double idle_seconds = 1.0;
    const EditorRun r = run_editor("haptics",
                                   R"([{"op": "set", "erosion": false, "depth": 0.01},
                                       {"op": "move", "at": [0.6, 0.5]},
                                       {"op": "haptics", "connect": true},
                                       {"op": "wait", "frames": 40}])",
                                   "--frames 1 --idle-seconds " + std::to_string(idle_seconds));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const auto& h = r.stats.at("haptics");
    EXPECT_GT(h.at("ticks").get<double>(), 200.0);
    EXPECT_FALSE(h.at("device_lost").get<bool>());
    // A loaded 2-core machine under Xvfb and lavapipe: only a loose bound on the rate here;
    // the loop's timing targets are measured by `sandtin bench haptics`.
    EXPECT_GT(h.at("rate_hz").get<double>(), 300.0);
    EXPECT_FALSE(h.at("stale").get<bool>());
    EXPECT_GT(h.at("force_n").get<double>(), 0.05);
    EXPECT_LE(h.at("force_n").get<double>(), 10.0);
    EXPECT_TRUE(h.at("contact").get<bool>());
    // The backup tick thread runs whenever a second CPU exists to cover the first.
    EXPECT_EQ(h.at("backup_thread").get<bool>(), std::thread::hardware_concurrency() >= 2);
    // Idle: the panel's readout is redrawn every kHapticReadoutSeconds, and nothing else is.
    const int idle_frames = r.stats.at("idle_submissions").get<int>();
    EXPECT_GE(idle_frames, 1);
    EXPECT_LE(idle_frames, static_cast<int>(idle_seconds / editor::kHapticReadoutSeconds) + 1);
}

TEST_F(EditorXvfb, AutosaveNewerThanTheSceneIsOfferedAndCanBeRecoveredOrDiscarded) {
    const fs::path scene = kWork / "recover.sandtin";
    ASSERT_EQ(run_editor("recover-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    // An autosave with one vertex raised by 3 cm, written after the scene.
    Session edited = load_session(scene);
    std::size_t raised = 0;
    while (!edited.terrain.vertices.alive[raised])
        ++raised;
    edited.terrain.vertices.height[raised] += 0.03;
    write_autosave(scene, edited);
    ASSERT_TRUE(find_autosave(scene).has_value());
    ASSERT_TRUE(find_autosave(scene)->offer_recovery());

    // Erosion paused: a raised vertex is far steeper than repose, and an opened document's
    // sand slides when the erosion runs (AnOpenedSceneSteeperThanReposeSlides).
    const fs::path recovered = kWork / "recovered.sandtin";
    const EditorRun r = run_editor("recover", R"([{"op": "set", "erosion": false},
                                                 {"op": "recovery", "choice": "recover"}])",
                                   scene.string() + " --save-after " + recovered.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const Session got = load_session(recovered);
    EXPECT_EQ(got.terrain.vertices.height, edited.terrain.vertices.height);
    // Saving (here to another file) leaves the scene's own autosave alone.
    ASSERT_TRUE(find_autosave(scene).has_value());

    const fs::path kept = kWork / "kept.sandtin";
    const EditorRun d = run_editor("discard", R"([{"op": "recovery", "choice": "discard"}])",
                                   scene.string() + " --save-after " + kept.string());
    ASSERT_EQ(d.exit_code, 0) << d.log;
    EXPECT_FALSE(find_autosave(scene).has_value());
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);

    // Without an autosave, answering the prompt is a clear error.
    const EditorRun e =
        run_editor("no-autosave", R"([{"op": "recovery", "choice": "recover"}])", scene.string());
    EXPECT_EQ(e.exit_code, 1) << e.log;
    EXPECT_NE(e.log.find("no autosave"), std::string::npos) << e.log;
}

TEST_F(EditorXvfb, UnsavedEditsGoToTheAutosaveAndLeaveTheSceneAlone) {
    const fs::path scene = kWork / "unsaved.sandtin";
    ASSERT_EQ(run_editor("unsaved-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    const std::vector<std::uint8_t> scene_bytes = read_file(scene);
    ASSERT_FALSE(find_autosave(scene).has_value());
    // Untouched: nothing unsaved, nothing to autosave.
    ASSERT_EQ(run_editor("unsaved-idle", R"([{"op": "autosave"}])", scene.string()).exit_code, 0);
    EXPECT_FALSE(find_autosave(scene).has_value());

    const EditorRun r =
        run_editor("unsaved", then(kStroke, R"({"op": "autosave"})"), scene.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(read_file(scene), scene_bytes) << "an autosave never touches the scene";
    const std::optional<AutosaveInfo> info = find_autosave(scene);
    ASSERT_TRUE(info.has_value());
    EXPECT_TRUE(info->offer_recovery()) << info->problem;
    // The stroke and the pour are in it: the terrain differs from the scene's.
    EXPECT_NE(recover_autosave(scene).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);
}

TEST_F(EditorXvfb, AFailingSessionKeepsItsEditsInTheAutosave) {
    const fs::path scene = kWork / "failing.sandtin";
    ASSERT_EQ(run_editor("failing-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    const std::string first = R"([{"op": "set", "erosion": false},
        {"op": "tool", "name": "Ball"}, {"op": "set", "radius": 0.05, "depth": 0.015},
        {"op": "drag", "path": [[0.45, 0.5], [0.75, 0.5]], "steps": 20}])";
    const std::string second = R"({"op": "drag", "path": [[0.5, 0.35], [0.5, 0.65]], "steps": 20})";
    // The oracle: the same two strokes in a session that ends normally, and the first alone
    // (so the comparison below can tell whether the second stroke reached the autosave).
    const fs::path both = kWork / "failing-both.sandtin";
    const fs::path one = kWork / "failing-one.sandtin";
    ASSERT_EQ(run_editor("failing-both", then(first, second),
                         scene.string() + " --save-after " + both.string())
                  .exit_code,
              0);
    ASSERT_EQ(run_editor("failing-one", first, scene.string() + " --save-after " + one.string())
                  .exit_code,
              0);
    const Session expected = load_session(both);
    ASSERT_NE(expected.terrain.vertices.height, load_session(one).terrain.vertices.height);

    // The session asks for autosaving after the first stroke, makes the second, then fails on
    // an op it cannot run: the error is reported, and the autosave written on the way out holds
    // both strokes, while the scene file stays as it was.
    const std::vector<std::uint8_t> scene_bytes = read_file(scene);
    const EditorRun r = run_editor("failing",
                                   then(then(first, R"({"op": "autosave"}, )" + second),
                                        R"({"op": "tool", "name": "NoSuchTool"})"),
                                   scene.string());
    EXPECT_EQ(r.exit_code, 1) << r.log;
    EXPECT_NE(r.log.find("unknown tool 'NoSuchTool'"), std::string::npos) << r.log;
    EXPECT_EQ(read_file(scene), scene_bytes);
    ASSERT_TRUE(find_autosave(scene).has_value()) << r.log;
    const Session kept = recover_autosave(scene);
    EXPECT_EQ(kept.terrain.vertices.alive, expected.terrain.vertices.alive);
    EXPECT_EQ(kept.terrain.vertices.position, expected.terrain.vertices.position);
    EXPECT_EQ(kept.terrain.vertices.height, expected.terrain.vertices.height);
    discard_autosave(scene);
}

TEST_F(EditorXvfb, NewAsksBeforeDroppingAnUntitledScenesEdits) {
    const fs::path fresh = kWork / "untitled-fresh.sandtin";
    ASSERT_EQ(run_editor("untitled-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const std::string press_new = R"({"op": "key", "key": "n", "ctrl": true}, )";

    // Cancel: the stroke and the pour stay, untouched by the Ctrl+Z pressed while the prompt
    // waited (shortcuts wait for the answer too).
    const fs::path stroked = kWork / "untitled-stroked.sandtin";
    ASSERT_EQ(run_editor("untitled-stroked", kStroke, "--save-after " + stroked.string()).exit_code,
              0);
    const fs::path kept = kWork / "untitled-kept.sandtin";
    const EditorRun c = run_editor(
        "untitled-cancel", then(kStroke, press_new + R"({"op": "key", "key": "z", "ctrl": true},
                                       {"op": "discard", "choice": "cancel"})"),
        "--save-after " + kept.string());
    ASSERT_EQ(c.exit_code, 0) << c.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
    EXPECT_NE(load_session(kept).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Discard: a new sandbox, as the editor starts with.
    const fs::path replaced = kWork / "untitled-new.sandtin";
    const EditorRun d = run_editor(
        "untitled-discard", then(kStroke, press_new + R"({"op": "discard", "choice": "discard"})"),
        "--save-after " + replaced.string());
    ASSERT_EQ(d.exit_code, 0) << d.log;
    EXPECT_EQ(load_session(replaced).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Nothing unsaved: Ctrl+N asks nothing, so there is nothing to answer.
    const EditorRun n = run_editor("untitled-nothing", R"([{"op": "key", "key": "n", "ctrl": true},
            {"op": "discard", "choice": "discard"}])");
    EXPECT_EQ(n.exit_code, 1) << n.log;
    EXPECT_NE(n.log.find("no unsaved edits"), std::string::npos) << n.log;
}

TEST_F(EditorXvfb, ClosingAsksBeforeDroppingAnUntitledScenesEdits) {
    // Whether the editor is still open after `ops`: their script ends with a save.
    auto stays_open = [](const std::string& name, const std::string& ops) {
        const fs::path probe = kWork / (name + ".sandtin");
        fs::remove(probe);
        const EditorRun r =
            run_editor(name, then(ops, R"({"op": "save", "path": ")" + probe.string() + R"("})"));
        EXPECT_EQ(r.exit_code, 0) << r.log;
        return fs::exists(probe);
    };
    const std::string close = R"({"op": "close"}, )";
    // Cancel: the editor stays open, and the script's next op still runs.
    EXPECT_TRUE(stays_open("close-cancel",
                           then(kStroke, close + R"({"op": "discard", "choice": "cancel"})")));
    // Discard: the editor closes before the next op.
    EXPECT_FALSE(stays_open("close-discard",
                            then(kStroke, close + R"({"op": "discard", "choice": "discard"})")));
    // Nothing unsaved: closing closes at once.
    EXPECT_FALSE(stays_open("close-clean", R"([{"op": "close"}])"));
}

// The unsaved-edits prompt offers Save too (it had only Discard and Cancel): it saves the
// untitled scene where Save and Ctrl+S would (the Scene field), then goes on; a save that
// fails keeps the scene and says why.
TEST_F(EditorXvfb, TheUnsavedEditsPromptCanSaveFirst) {
    const fs::path fresh = kWork / "prompt-fresh.sandtin";
    ASSERT_EQ(run_editor("prompt-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const fs::path stroked = kWork / "prompt-stroked.sandtin";
    ASSERT_EQ(run_editor("prompt-stroked", kStroke, "--save-after " + stroked.string()).exit_code,
              0);
    const auto save_to = [](const fs::path& p) {
        return R"({"op": "set", "scene_path": ")" + p.string() + R"("}, )";
    };
    const std::string press_new = R"({"op": "key", "key": "n", "ctrl": true}, )";

    // Save and New: the edits are in the file, and the editor holds a new sandbox.
    const fs::path saved = kWork / "prompt-saved.sandtin";
    const fs::path after_new = kWork / "prompt-after-new.sandtin";
    fs::remove(saved);
    const EditorRun s = run_editor(
        "prompt-save-new",
        then(kStroke, save_to(saved) + press_new + R"({"op": "discard", "choice": "save"})"),
        "--save-after " + after_new.string());
    ASSERT_EQ(s.exit_code, 0) << s.log;
    ASSERT_TRUE(fs::exists(saved)) << s.log;
    EXPECT_EQ(load_session(saved).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
    EXPECT_EQ(load_session(after_new).terrain.vertices.height,
              load_session(fresh).terrain.vertices.height);

    // Save and Quit: saved, and the editor closed before the script's next op.
    const fs::path quit_saved = kWork / "prompt-quit-saved.sandtin";
    const fs::path probe = kWork / "prompt-quit-probe.sandtin";
    fs::remove(quit_saved);
    fs::remove(probe);
    const EditorRun q = run_editor(
        "prompt-save-quit",
        then(kStroke, save_to(quit_saved) + R"({"op": "close"}, {"op": "discard", "choice": "save"},
            {"op": "save", "path": ")" +
                          probe.string() + R"("})"));
    ASSERT_EQ(q.exit_code, 0) << q.log;
    EXPECT_TRUE(fs::exists(quit_saved)) << q.log;
    EXPECT_FALSE(fs::exists(probe)) << "the editor stayed open after Save and Quit";

    // A save that fails (a name that claims another format): the scene and its edits stay.
    const fs::path kept = kWork / "prompt-kept.sandtin";
    ::setenv("SANDTIN_EDITOR_TRACE", "1", 1);  // the status line's reports go to the log
    const EditorRun f = run_editor("prompt-save-fails",
                                   then(kStroke, save_to(kWork / "x.png") + press_new +
                                                     R"({"op": "discard", "choice": "save"})"),
                                   "--save-after " + kept.string());
    ::unsetenv("SANDTIN_EDITOR_TRACE");
    ASSERT_EQ(f.exit_code, 0) << f.log;
    EXPECT_NE(f.log.find("save failed"), std::string::npos) << f.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(stroked).terrain.vertices.height);
}

TEST_F(EditorXvfb, AnAutosaveThatCannotBeRebuiltLeavesTheSceneOpen) {
    const fs::path scene = kWork / "bad-autosave.sandtin";
    ASSERT_EQ(run_editor("bad-autosave-base", kFlat, "--save-after " + scene.string()).exit_code,
              0);
    // The file loads (so recovery is offered) but its triangles do not tile the domain: one
    // finite triangle turned clockwise.
    Session damaged = load_session(scene);
    for (auto& corners : damaged.terrain.slots) {
        if (corners[0] < kOutsideCorner && corners[1] < kOutsideCorner &&
            corners[2] < kOutsideCorner) {
            std::swap(corners[0], corners[1]);
            break;
        }
    }
    write_autosave(scene, damaged);
    ASSERT_TRUE(find_autosave(scene)->offer_recovery());
    const fs::path kept = kWork / "bad-autosave-kept.sandtin";
    const EditorRun r = run_editor("bad-autosave", R"([{"op": "recovery", "choice": "recover"}])",
                                   scene.string() + " --save-after " + kept.string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(load_session(kept).terrain.vertices.height,
              load_session(scene).terrain.vertices.height);
}

TEST_F(EditorXvfb, AnUnwritableSettingsFileIsReportedAndTheSessionGoesOn) {
    // The settings file's folder is a regular file: writing the settings must fail.
    const fs::path blocker = kWork / "not-a-folder";
    std::ofstream(blocker) << "x";
    const fs::path saved = kWork / "after-settings.sandtin";
    fs::remove(saved);
    const std::string ops = R"([{"op": "set", "erosion": false}, {"op": "save_settings"},
        {"op": "save", "path": ")" +
                            saved.string() + R"("}])";
    const EditorRun r =
        run_editor("unwritable-settings", ops, "--settings " + (blocker / "s.json").string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
    EXPECT_TRUE(fs::exists(saved)) << "the script went on after the failed settings write";
}

TEST_F(EditorXvfb, ResizingTheWindowRebuildsTheSwapchainCleanly) {
    const fs::path shot = kWork / "resized.png";
    const EditorRun r = run_editor("resize",
                                   R"([{"op": "set", "erosion": false},
                                       {"op": "resize", "size": [800, 600]},
                                       {"op": "wait", "frames": 4}])",
                                   "--frames 2 --screenshot " + shot.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const PngImage im = read_png(shot);
    EXPECT_EQ(im.width, 800u);
    EXPECT_EQ(im.height, 600u);
    // Still a terrain in the middle of the new frame (not the clear colour everywhere).
    double sum = 0, sum2 = 0;
    int n = 0;
    for (std::uint32_t y = 250; y < 350; ++y) {
        for (std::uint32_t x = 450; x < 650; ++x) {
            const double l = luminance(pixel(im, x, y));
            sum += l;
            sum2 += l * l;
            ++n;
        }
    }
    EXPECT_GT(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 3.0);
}

TEST_F(EditorXvfb, AutoPutsTheRelaxationWhereTheDeviceIsFasterAndSaysWhere) {
    const fs::path settings = kWork / "auto-physics.settings.json";
    fs::remove(settings);
    const EditorRun r = run_editor("auto-physics", kFlat, "--settings " + settings.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // The device decides: a software rasteriser (lavapipe's "(CPU, ..." in the log) keeps the
    // relaxation on the CPU; a hardware GPU takes it.
    const bool software = r.log.find("(CPU, Vulkan") != std::string::npos;
    EXPECT_EQ(r.stats.at("physics").get<std::string>(), software ? "cpu" : "gpu") << r.log;
    const std::string first = r.stats.at("messages").at(0).get<std::string>();
    EXPECT_NE(first.find(software ? "relaxation on the CPU (Auto: " : "relaxation on the GPU"),
              std::string::npos)
        << first;
}

TEST_F(EditorXvfb, IdleEditorSubmitsNothing) {
    const EditorRun r = run_editor("idle", kFlat, "--frames 2 --idle-seconds 2");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("idle_submissions").get<int>(), 0);
    EXPECT_EQ(r.stats.at("idle_gpu_work").get<int>(), 0);
    EXPECT_GT(r.stats.at("submissions").get<int>(), 0);
    // With the GPU relaxation after a pour has come to rest: no frame, bake, upload or
    // dispatch either.
    const EditorRun g = run_editor("idle-gpu", R"([{"op": "set", "physics": "gpu"},
        {"op": "tool", "name": "Pour"}, {"op": "click", "at": [0.5, 0.5]},
        {"op": "erode", "frames": 30}])",
                                   "--frames 2 --idle-seconds 2");
    ASSERT_EQ(g.exit_code, 0) << g.log;
    EXPECT_EQ(g.stats.at("physics").get<std::string>(), "gpu");
    EXPECT_EQ(g.stats.at("idle_submissions").get<int>(), 0);
    EXPECT_EQ(g.stats.at("idle_gpu_work").get<int>(), 0);
}

// Every window the editor grew for everyday work (Help, the file browser, the progress bar)
// opened and closed again: the idle editor still submits nothing, does no GPU work, and spends
// under 1 % of a CPU (every thread of the process, the Vulkan driver's included).
TEST_F(EditorXvfb, AfterItsWindowsCloseTheEditorIdlesAtNoCost) {
    const fs::path scene = kWork / "idle-windows.sandtin";
    save_flat_scene(scene, 1.0, unit_square_points(200, 31));
    const fs::path grid = kWork / "idle-windows.asc";
    {
        std::ofstream out(grid);
        out << "ncols 40\nnrows 40\nxllcorner 0\nyllcorner 0\ncellsize 0.025\n";
        for (int y = 0; y < 40; ++y) {
            for (int x = 0; x < 40; ++x)
                out << 0.001 * ((x * 7 + y * 3) % 11) << (x + 1 < 40 ? " " : "\n");
        }
    }
    const std::string ops = then(kFlat, R"({"op": "key", "key": "f1"}, {"op": "wait", "frames": 2},
        {"op": "key", "key": "f1"}, {"op": "wait", "frames": 2},
        {"op": "pick_file", "dialog": "open", "path": ")" +
                                            scene.string() +
                                            R"(", "cancel": true},
        {"op": "wait", "frames": 2},
        {"op": "set", "import_path": ")" + grid.string() +
                                            R"("},
        {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 4})");
    const EditorRun r = run_editor("idle-windows", ops, "--frames 2 --idle-seconds 2");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    ASSERT_EQ(r.stats.at("jobs").size(), 1u) << "the import did not run as a job";
    EXPECT_EQ(r.stats.at("jobs")[0].at("outcome"), "done");
    EXPECT_GE(r.stats.at("jobs")[0].at("bar_frames").get<int>(), 1);
    EXPECT_EQ(r.stats.at("idle_submissions").get<int>(), 0);
    EXPECT_EQ(r.stats.at("idle_gpu_work").get<int>(), 0);
    EXPECT_LT(r.stats.at("idle_cpu_share").get<double>(), 0.01);
}

// The Erosion panel's GPU switch: sand poured with erosion paused, then eroded by the GPU
// physics inside the editor. Oracle: the CPU Jacobi schedule (physics/SandPhysics, a second
// implementation) run to rest from the saved pre-erosion scene. r_S = 5 cm keeps refinement
// (which the two place differently) out of the comparison.
const char* kGpuErosion = R"([
    {"op": "set", "erosion": false, "physics": "gpu", "relocation_radius": 0.05, "steps": 64},
    {"op": "tool", "name": "Pour"}, {"op": "set", "pour_volume": 0.00005},
    {"op": "click", "at": [0.5, 0.5]}, {"op": "click", "at": [0.5, 0.5]},
    {"op": "wait", "frames": 1}, {"op": "save", "path": "@BEFORE@"},
    {"op": "erode", "frames": 60}, {"op": "save", "path": "@AFTER@"},
    {"op": "save_settings"}])";

TEST_F(EditorXvfb, GpuErosionRelaxesLikeTheCpuJacobiReferenceAndTheSwitchPersists) {
    const fs::path before = kWork / "gpu-before.sandtin", after = kWork / "gpu-after.sandtin";
    const fs::path settings = kWork / "gpu-settings.json";
    fs::remove(settings);
    std::string ops = kGpuErosion;
    ops.replace(ops.find("@BEFORE@"), 8, before.string());
    ops.replace(ops.find("@AFTER@"), 7, after.string());
    const EditorRun r = run_editor("gpu-erosion", ops, "--settings " + settings.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("physics").get<std::string>(), "gpu");

    const Session s0 = load_session(before), s1 = load_session(after);
    const Tin t0 = Tin::from_snapshot(s0.terrain), gpu = Tin::from_snapshot(s1.terrain);
    Tin cpu = Tin::from_snapshot(s0.terrain);
    TalusSettings jacobi;
    jacobi.schedule = Schedule::Jacobi;
    SandPhysics reference(cpu, MaterialTable::presets(), jacobi);
    reference.settings().parameters.relocation_radius = 0.05;
    reference.activate_all();
    ASSERT_TRUE(reference.run_to_rest(200000).at_rest);

    // Compare the surfaces on a grid around the pour (the cursor) and far from it.
    const auto cur = r.stats.at("cursor");
    const Vec2 c{cur[0].get<double>(), cur[1].get<double>()};
    double lowered = 0.0, worst = 0.0;
    for (int i = -40; i <= 40; ++i) {
        for (int j = -40; j <= 40; ++j) {
            const Vec2 p{c.x + 0.002 * i, c.y + 0.002 * j};
            const auto h0 = t0.height_at(p), hg = gpu.height_at(p), hc = cpu.height_at(p);
            if (!h0 || !hg || !hc) continue;
            lowered = std::max(lowered, *h0 - *hg);
            worst = std::max(worst, std::abs(*hg - *hc));
        }
    }
    std::printf("GPU erosion: pile lowered by %.3f mm, largest GPU-CPU difference %.4f mm\n",
                lowered * 1e3, worst * 1e3);
    EXPECT_GT(lowered, 0.005) << "the GPU erosion did not flatten the poured pile";
    EXPECT_LT(worst, 0.05 * lowered) << "GPU and CPU Jacobi rest states differ";
    EXPECT_NEAR(gpu.volume(), t0.volume(), 1e-6 * t0.volume()) << "volume not conserved";

    // The switch persists: a new run with the same settings file starts on the GPU.
    const EditorRun again = run_editor("gpu-again", kFlat, "--settings " + settings.string());
    ASSERT_EQ(again.exit_code, 0) << again.log;
    EXPECT_EQ(again.stats.at("physics").get<std::string>(), "gpu");
}

// A Materials-panel edit is an undo level and travels with the scene: saved after the edit,
// after undoing it and after redoing it, then reopened and saved again. The File panel's
// Export writes the edited colour (it once wrote the presets' whatever the panel said).
TEST_F(EditorXvfb, MaterialEditsAreUndoLevelsAndAreSavedWithTheScene) {
    const fs::path edited = kWork / "mat-edited.sandtin", undone = kWork / "mat-undone.sandtin",
                   redone = kWork / "mat-redone.sandtin", reopened = kWork / "mat-reopened.sandtin";
    std::string ops = R"([{"op": "set", "erosion": false},
        {"op": "material", "index": 0, "repose_dry": 21.5, "colour": [0.3, 0.5, 0.9]},
        {"op": "wait", "frames": 1}, {"op": "save", "path": "@1@"},
        {"op": "export", "path": "@4@"},
        {"op": "key", "key": "z", "ctrl": true}, {"op": "save", "path": "@2@"},
        {"op": "key", "key": "y", "ctrl": true}, {"op": "save", "path": "@3@"}])";
    ops.replace(ops.find("@1@"), 3, edited.string());
    ops.replace(ops.find("@2@"), 3, undone.string());
    ops.replace(ops.find("@3@"), 3, redone.string());
    const fs::path exported = kWork / "mat-edited.obj";
    fs::remove(kWork / "mat-edited.mtl");
    ops.replace(ops.find("@4@"), 3, exported.string());
    const EditorRun r = run_editor("materials", ops);
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // The sandbox is one material: the OBJ's material is its colour, as edited.
    std::ifstream mtl(kWork / "mat-edited.mtl");
    std::string line;
    std::array<double, 3> kd{-1.0, -1.0, -1.0};
    while (std::getline(mtl, line)) {
        if (line.rfind("Kd ", 0) == 0)
            std::istringstream(line.substr(3)) >> kd[0] >> kd[1] >> kd[2];
    }
    EXPECT_NEAR(kd[0], 0.3, 1e-6);
    EXPECT_NEAR(kd[1], 0.5, 1e-6);
    EXPECT_NEAR(kd[2], 0.9, 1e-6);
    const auto table = [](const fs::path& p) {
        const auto t = materials_from_metadata(load_session(p).metadata_json);
        EXPECT_TRUE(t.has_value()) << p;
        return t.value_or(MaterialTable{});
    };
    const double presets_dry = MaterialTable::presets().at(0).repose_dry;
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    EXPECT_NEAR(table(edited).at(0).repose_dry, 21.5 * kDeg, 1e-9);
    EXPECT_FLOAT_EQ(table(edited).at(0).colour[2], 0.9f);
    EXPECT_NEAR(table(undone).at(0).repose_dry, presets_dry, 1e-9);
    EXPECT_FLOAT_EQ(table(undone).at(0).colour[2], MaterialTable::presets().at(0).colour[2]);
    EXPECT_NEAR(table(redone).at(0).repose_dry, 21.5 * kDeg, 1e-9);
    // The other materials are untouched throughout.
    EXPECT_NEAR(table(redone).at(2).repose_dry, MaterialTable::presets().at(2).repose_dry, 1e-9);

    const EditorRun again = run_editor("materials-reopen", kFlat,
                                       redone.string() + " --save-after " + reopened.string());
    ASSERT_EQ(again.exit_code, 0) << again.log;
    EXPECT_NEAR(table(reopened).at(0).repose_dry, 21.5 * kDeg, 1e-9);
}

// The settings are made for the 1 m sandbox; on a terrain 100 times larger the editor scales
// every length (and the pour's volume by 100³). The oracle is similarity: the talus rule has
// no length scale, so the same script on the same points, 100 times farther apart, must give
// the same terrain 100 times larger. (Before the scaling, the 100 m terrain got a 4 cm groove,
// a 20 cm³ pour, and a 1 cm r_S that refined 20 000 vertices into 204 000.)
TEST_F(EditorXvfb, ToolsPourAndRelocationRadiusFollowTheTerrainsSize) {
    const std::vector<Vec2> unit_points = unit_square_points(6000, 12345);
    const std::string ops = R"([{"op": "set", "erosion": true},
        {"op": "tool", "name": "Ball"},
        {"op": "drag", "path": [[0.4, 0.5], [0.65, 0.5]], "steps": 20},
        {"op": "tool", "name": "Pour"}, {"op": "click", "at": [0.55, 0.35]},
        {"op": "erode", "frames": 40}, {"op": "save_settings"}])";
    struct Result {
        Tin tin;
        std::string log;
        editor::EditorSettings settings;
    };
    auto run_on = [&](double size) {
        const std::string name = "scale-" + std::to_string(static_cast<int>(size));
        std::vector<Vec2> points;
        for (Vec2 p : unit_points)
            points.push_back(p * size);
        const fs::path scene = kWork / (name + ".sandtin");
        const fs::path after = kWork / (name + "-after.sandtin");
        const fs::path settings = kWork / (name + "-settings.json");
        save_flat_scene(scene, size, points);
        fs::remove(settings);  // the defaults, made for the 1 m sandbox
        // The trace puts the status line's reports in the log.
        ::setenv("SANDTIN_EDITOR_TRACE", "1", 1);
        const EditorRun r = run_editor(name, ops,
                                       scene.string() + " --settings " + settings.string() +
                                           " --save-after " + after.string());
        ::unsetenv("SANDTIN_EDITOR_TRACE");
        EXPECT_EQ(r.exit_code, 0) << r.log;
        return Result{Tin::from_snapshot(load_session(after).terrain), r.log,
                      editor::load_settings(settings)};
    };
    const Result small = run_on(1.0);
    const Result large = run_on(100.0);
    ASSERT_TRUE(small.tin.check_valid().ok()) << small.tin.check_valid().summary();
    ASSERT_TRUE(large.tin.check_valid().ok()) << large.tin.check_valid().summary();

    const editor::EditorSettings defaults;
    EXPECT_EQ(small.settings.scene_size, 1.0);
    EXPECT_EQ(small.settings.tool_radius, defaults.tool_radius);
    EXPECT_EQ(large.settings.scene_size, 100.0);
    EXPECT_NEAR(large.settings.tool_radius, 100.0 * defaults.tool_radius, 1e-12);
    EXPECT_NEAR(large.settings.relocation_radius, 100.0 * defaults.relocation_radius, 1e-12);
    EXPECT_NEAR(large.settings.pour_volume, 1e6 * defaults.pour_volume, 1e-9);
    EXPECT_NE(large.log.find("scaled x100 for this 100 m terrain"), std::string::npos) << large.log;
    EXPECT_EQ(small.log.find("scaled x"), std::string::npos) << small.log;

    // The pour is the only volume added (the Ball's ridge conserves what it digs).
    const double v_small = small.tin.volume(), v_large = large.tin.volume();
    EXPECT_NEAR(v_small, defaults.pour_volume, 0.01 * defaults.pour_volume);
    EXPECT_NEAR(v_large / v_small, 1e6, 1e6 * 0.01);
    // The same detail: as many vertices (the simplification and r_S refinement scaled too).
    const double n_small = static_cast<double>(small.tin.vertex_count());
    const double n_large = static_cast<double>(large.tin.vertex_count());
    EXPECT_NEAR(n_large / n_small, 1.0, 0.05) << n_small << " vs " << n_large;
    // The same relief, 100 times taller and deeper.
    auto extremes = [](const Tin& tin) {
        double lo = 1e300, hi = -1e300;
        const VertexArrays& va = tin.vertices();
        for (std::size_t i = 0; i < va.size(); ++i) {
            if (!va.alive[i]) continue;
            lo = std::min(lo, va.height[i]);
            hi = std::max(hi, va.height[i]);
        }
        return std::pair{lo, hi};
    };
    const auto [lo_small, hi_small] = extremes(small.tin);
    const auto [lo_large, hi_large] = extremes(large.tin);
    ASSERT_LT(lo_small, -0.5 * defaults.tool_depth);  // the groove is there
    ASSERT_GT(hi_small, 0.005);                       // and the pile
    EXPECT_NEAR(lo_large / lo_small, 100.0, 5.0);
    EXPECT_NEAR(hi_large / hi_small, 100.0, 5.0);
}

// Pour and Remove move sand by the gesture, not by the mouse events that delivered it: a drag
// pours one dab where it starts and one every half pour radius along its path (the script's
// pour path spacing), and a button held still pours four dabs a second (a scripted frame
// counts 1/60 s). Before, every mouse-move event poured a dab: the same drag poured 4 dabs as
// 3 events and 42 as 41, and a held button poured once.
class EditorPour : public EditorXvfb {
  protected:
    static constexpr double kDab = 1e-6;  ///< m³, the Pour slider
    /// The volume a script's Pour gesture adds to a flat 1 m scene, from above.
    double poured(const std::string& name, const std::string& gesture) {
        const fs::path scene = kWork / "pour-flat.sandtin";
        if (!fs::exists(scene)) save_flat_scene(scene, 1.0, unit_square_points(6000, 99));
        const fs::path after = kWork / (name + "-after.sandtin");
        const std::string ops =
            R"([{"op": "set", "erosion": false, "radius": 0.04, "pour_volume": )" +
            std::to_string(kDab) + R"(}, {"op": "camera", "pitch": 1.5},
            {"op": "tool", "name": "Pour"}, )" +
            gesture + "]";
        const EditorRun r =
            run_editor(name, ops, scene.string() + " --save-after " + after.string());
        EXPECT_EQ(r.exit_code, 0) << r.log;
        return Tin::from_snapshot(load_session(after).terrain).volume();
    }
};

TEST_F(EditorPour, ADragPoursTheSameWhateverTheNumberOfMouseEvents) {
    const std::string path = R"({"op": "drag", "path": [[0.45, 0.45], [0.6, 0.55]], "steps": )";
    const double few = poured("pour-drag-3", path + "3}");
    const double many = poured("pour-drag-41", path + "41}");
    const double dabs = std::round(few / kDab);
    EXPECT_GE(dabs, 5.0) << "the drag should be several dab spacings long";
    EXPECT_NEAR(few, dabs * kDab, 1e-3 * kDab) << "not a whole number of dabs";
    EXPECT_NEAR(many, few, 1e-3 * kDab) << "3 events poured " << few << " m³, 41 poured " << many;
}

TEST_F(EditorPour, HoldingTheButtonStillKeepsPouringFourDabsASecond) {
    // A click: one dab. Held for 40 and 100 frames of waiting, plus the press's and the
    // wait's own frames: 0.7 s and 1.7 s, so 2 and 6 more dabs.
    const auto hold = [](int frames) {
        return R"({"op": "press", "at": [0.6, 0.5]}, {"op": "wait", "frames": )" +
               std::to_string(frames) + R"(}, {"op": "release"})";
    };
    EXPECT_NEAR(poured("pour-click", R"({"op": "click", "at": [0.6, 0.5]})"), kDab, 1e-3 * kDab);
    EXPECT_NEAR(poured("pour-hold-40", hold(40)), 3.0 * kDab, 1e-3 * kDab);
    EXPECT_NEAR(poured("pour-hold-100", hold(100)), 7.0 * kDab, 1e-3 * kDab);
}

// A Remove that finds less sand above the bedrock than it asks for says so, with the words
// `sandtin run` uses (it used to be silent): 200 cm³ asked of a 5 mm disc on the sandbox.
TEST_F(EditorPour, ARemoveThatFindsLessSandThanAskedSaysSo) {
    const std::string ops = R"([{"op": "set", "erosion": false, "radius": 0.01,
        "pour_volume": 0.0002}, {"op": "tool", "name": "Remove"},
        {"op": "click", "at": [0.6, 0.5]}])";
    ::setenv("SANDTIN_EDITOR_TRACE", "1", 1);  // the status line's reports go to the log
    const EditorRun r = run_editor("remove-short", ops);
    ::unsetenv("SANDTIN_EDITOR_TRACE");
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_NE(r.log.find("of the 0.0002 m³ asked: there is no more sand above the bedrock"),
              std::string::npos)
        << r.log;
}

// The panel's simplification tolerance holds for a scene opened during the session too, not
// only for the one the editor started with: the same stroke after Ctrl+O re-opens the scene
// must leave the same terrain as without it. (Each opened document used to get the engine's
// default tolerance while the panel still showed the artist's.)
TEST_F(EditorXvfb, AnOpenedSceneIsSimplifiedWithThePanelsTolerance) {
    const fs::path scene = kWork / "reopen.sandtin";
    ASSERT_EQ(run_editor("reopen-base", kFlat, "--save-after " + scene.string()).exit_code, 0);
    const fs::path settings = kWork / "reopen-settings.json";
    editor::EditorSettings coarse;
    coarse.simplify_tolerance = 0.004;  // 8 times the default: far fewer vertices
    editor::save_settings(settings, coarse);
    const std::string stroke = R"({"op": "tool", "name": "Ball"},
        {"op": "drag", "path": [[0.45, 0.5], [0.75, 0.5]], "steps": 20})";
    auto run = [&](const std::string& name, const std::string& ops,
                   const fs::path& with = fs::path()) {
        const fs::path after = kWork / (name + "-after.sandtin");
        const EditorRun r =
            run_editor(name, ops,
                       scene.string() + " --settings " + (with.empty() ? settings : with).string() +
                           " --save-after " + after.string());
        EXPECT_EQ(r.exit_code, 0) << r.log;
        return load_session(after).terrain;
    };
    const TinSnapshot direct = run("reopen-direct", then(kFlat, stroke));
    // The tolerance matters: the default one keeps more of the stroke's vertices.
    const fs::path defaults = kWork / "reopen-defaults.json";
    editor::save_settings(defaults, editor::EditorSettings{});
    const TinSnapshot fine = run("reopen-fine", then(kFlat, stroke), defaults);
    auto alive = [](const TinSnapshot& t) {
        return std::count(t.vertices.alive.begin(), t.vertices.alive.end(), 1);
    };
    EXPECT_LT(alive(direct), alive(fine));
    const TinSnapshot reopened =
        run("reopen-again", then(kFlat, R"({"op": "key", "key": "o", "ctrl": true}, )" + stroke));
    EXPECT_EQ(reopened.vertices.position, direct.vertices.position);
    EXPECT_EQ(reopened.vertices.height, direct.vertices.height);
}

// Detail follows the work after the erosion too: once a pour has slid to rest, what the sand
// moved and what r_S refined is simplified, as an edit's vertices are, and the sand settles
// what that steepened before the erosion becomes an undo level. The oracle is the script
// runner's `erode` with `until_rest` (engine/io/script.cpp), which does the same with the same
// pour on the same terrain. Without the simplification the editor added 414 vertices, the
// script 262.
TEST_F(EditorXvfb, ErodedGroundIsSimplifiedOnceTheSandRests) {
    const std::vector<Vec2> points = unit_square_points(3000, 777);
    const fs::path scene = kWork / "erode-simplify.sandtin";
    const fs::path after = kWork / "erode-simplify-after.sandtin";
    const Session session = save_flat_scene(scene, 1.0, points);
    const double volume = 1e-4;  // m³: a pile about 3 cm high and 11 cm across
    const std::string ops = R"([{"op": "set", "erosion": false, "pour_volume": 0.0001},
        {"op": "tool", "name": "Pour"}, {"op": "click", "at": [0.5, 0.5]},
        {"op": "set", "erosion": true}, {"op": "erode", "frames": 400}])";
    const EditorRun r =
        run_editor("erode-simplify", ops, scene.string() + " --save-after " + after.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const Tin edited = Tin::from_snapshot(load_session(after).terrain);
    ASSERT_TRUE(edited.check_valid().ok()) << edited.check_valid().summary();
    EXPECT_NEAR(edited.volume(), volume, 1e-3 * volume);
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    EXPECT_LE(test::steepest_edge_ratio(edited, tan_alpha), 1.0 + 1e-3);  // at rest, after all

    // The same pour where the editor's landed (the apex), through the script runner.
    const VertexArrays& va = edited.vertices();
    std::uint32_t apex = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v] && va.height[v] > va.height[apex]) apex = v;
    }
    const editor::EditorSettings defaults;
    const Vec2 at = va.position[apex];
    const std::string text =
        R"({"settings": {"relocation_radius": )" + std::to_string(defaults.relocation_radius) +
        R"(}, "operations": [{"op": "pour", "at": [)" + std::to_string(at.x) + ", " +
        std::to_string(at.y) + R"(], "volume": 0.0001, "radius": )" +
        std::to_string(0.5 * defaults.tool_radius) + R"(}, {"op": "erode", "until_rest": true}]})";
    const Script script = parse_script(text, "pour", ".");
    Tin scripted = Tin::from_snapshot(session.terrain);
    SculptContext context(scripted.domain());
    ScriptRunner runner(script, scripted, context);
    for (const ScriptStep& step : script.steps)
        runner.run(step);
    auto added = [&](const Tin& tin) {
        return static_cast<double>(tin.vertex_count()) - static_cast<double>(points.size());
    };
    RecordProperty("vertices_added_editor", static_cast<int>(added(edited)));
    RecordProperty("vertices_added_script", static_cast<int>(added(scripted)));
    EXPECT_NEAR(added(edited) / added(scripted), 1.0, 0.15)
        << added(edited) << " vertices added in the editor, " << added(scripted)
        << " by the script";
    EXPECT_NEAR(va.height[apex], *scripted.height_at(at), 0.03 * va.height[apex]);
}

// An opened scene steeper than repose slides once the erosion runs: the physics used to start
// with nothing active on an opened document, so the slope stood (and the Stats panel said the
// sand rested) until a tool touched it. Oracles: the physics' own bound on every edge once at
// rest, and the volume.
TEST_F(EditorXvfb, AnOpenedSceneSteeperThanReposeSlides) {
    // A cone 3 cm high and 3 cm across its foot (45 degrees, against a repose of 32), with
    // points enough on its flanks.
    std::vector<Vec2> points = unit_square_points(3000, 778);
    const Vec2 centre{0.5, 0.5};
    for (const Vec2 p : unit_square_points(300, 779))
        points.push_back(centre + 0.06 * (p - Vec2{0.5, 0.5}));
    std::vector<double> heights;
    for (const Vec2 p : points)
        heights.push_back(std::max(0.0, 0.03 - distance(p, centre)));
    const fs::path scene = kWork / "steep-open.sandtin";
    const fs::path after = kWork / "steep-open-after.sandtin";
    Session session;
    session.terrain = Tin::from_points(Rect::from_size(1.0, 1.0), points, heights).snapshot();
    save_session(scene, session);
    const Tin before = Tin::from_snapshot(session.terrain);
    const double tan_alpha = MaterialTable::presets().at(0).talus_slope(0.0);
    ASSERT_GT(test::steepest_edge_ratio(before, tan_alpha), 1.05);
    const EditorRun r = run_editor("steep-open", R"([{"op": "erode", "frames": 400}])",
                                   scene.string() + " --save-after " + after.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const Tin eroded = Tin::from_snapshot(load_session(after).terrain);
    ASSERT_TRUE(eroded.check_valid().ok()) << eroded.check_valid().summary();
    EXPECT_NEAR(eroded.volume(), before.volume(), 1e-9 * before.volume());
    EXPECT_LE(test::steepest_edge_ratio(eroded, tan_alpha), 1.0 + 1e-3);
}

/// Heights by position of the vertices two terrains share (positions are exact in a session).
std::vector<std::pair<double, double>> shared_heights(const Tin& before, const Tin& after,
                                                      std::vector<Vec2>* where) {
    std::map<std::pair<double, double>, double> h0;
    const VertexArrays& v0 = before.vertices();
    for (std::size_t i = 0; i < v0.size(); ++i) {
        if (v0.alive[i]) h0[{v0.position[i].x, v0.position[i].y}] = v0.height[i];
    }
    std::vector<std::pair<double, double>> out;
    const VertexArrays& v1 = after.vertices();
    for (std::size_t i = 0; i < v1.size(); ++i) {
        if (!v1.alive[i]) continue;
        const auto it = h0.find({v1.position[i].x, v1.position[i].y});
        if (it == h0.end()) continue;
        out.push_back({it->second, v1.height[i]});
        where->push_back(v1.position[i]);
    }
    return out;
}

TEST_F(EditorXvfb, LowerFlattenFootAndWeatherToolsDoWhatTheirNamesSay) {
    // One run, a save after each tool, with a settings file of its own. Simplification only
    // of exactly planar patches, which moves no volume: otherwise a removal would shift the
    // heights around it to keep the volume, and blur the exact oracles below.
    const fs::path s0 = kWork / "brushes-0.sandtin", s1 = kWork / "brushes-1.sandtin",
                   s2 = kWork / "brushes-2.sandtin", s3 = kWork / "brushes-3.sandtin",
                   s4 = kWork / "brushes-4.sandtin";
    const auto save = [](const fs::path& p) {
        return R"({"op": "save", "path": ")" + p.string() + R"("})";
    };
    constexpr double kRadius = 0.05, kLower = 0.01;
    const std::string ops =
        R"([{"op": "set", "erosion": false, "radius": 0.05, "depth": 0.01,
                    "simplify_tolerance": 0},
            {"op": "wait", "frames": 1}, )" +
        save(s0) + R"(, {"op": "tool", "name": "Lower"},
            {"op": "set", "brush_strength": 0.01, "falloff": "constant"},
            {"op": "click", "at": [0.5, 0.5]}, )" +
        save(s1) + R"(, {"op": "tool", "name": "Flatten"},
            {"op": "set", "brush_blend": 1.0, "falloff": "constant"},
            {"op": "drag", "path": [[0.45, 0.58], [0.55, 0.58]], "steps": 1}, )" +
        save(s2) + R"(, {"op": "tool", "name": "Foot"},
            {"op": "drag", "path": [[0.6, 0.42], [0.72, 0.45]], "steps": 12}, )" +
        save(s3) + R"(, {"op": "tool", "name": "Weather"},
            {"op": "set", "brush_blend": 1.0, "falloff": "constant"},
            {"op": "drag", "path": [[0.55, 0.7], [0.7, 0.7]], "steps": 16}, )" +
        save(s4) + "]";
    const fs::path settings = kWork / "brushes-settings.json";
    fs::remove(settings);
    const EditorRun r = run_editor("brushes", ops, "--settings " + settings.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const Tin t0 = Tin::from_snapshot(load_session(s0).terrain);
    const Tin t1 = Tin::from_snapshot(load_session(s1).terrain);
    const Tin t2 = Tin::from_snapshot(load_session(s2).terrain);
    const Tin t3 = Tin::from_snapshot(load_session(s3).terrain);
    const Tin t4 = Tin::from_snapshot(load_session(s4).terrain);

    {
        // Lower with a constant falloff: the vertices within the radius of the dab went down
        // by the brush height, the others did not move.
        std::vector<Vec2> at;
        const auto h = shared_heights(t0, t1, &at);
        std::vector<Vec2> lowered;
        for (std::size_t i = 0; i < h.size(); ++i) {
            const double dz = h[i].second - h[i].first;
            if (dz == 0.0) continue;
            EXPECT_NEAR(dz, -kLower, 1e-12) << at[i].x << " " << at[i].y;
            lowered.push_back(at[i]);
        }
        ASSERT_GT(lowered.size(), 20u);
        Vec2 c{0.0, 0.0};
        for (const Vec2 p : lowered)
            c = c + p * (1.0 / static_cast<double>(lowered.size()));
        for (std::size_t i = 0; i < h.size(); ++i) {
            const double d = distance(at[i], c);
            if (d < 0.85 * kRadius) {
                EXPECT_NE(h[i].second, h[i].first) << d;
            } else if (d > 1.15 * kRadius) {
                EXPECT_EQ(h[i].second, h[i].first) << d;
            }
        }
        // Volume: the brush height over the disc, to the TIN's resolution of its rim.
        const double disc = kLower * 3.14159265358979 * kRadius * kRadius;
        EXPECT_NEAR(t1.volume() - t0.volume(), -disc, 0.25 * disc);
    }
    {
        // Flatten at full strength with a constant falloff: everything the stroke moved now
        // sits at one level, the surface where the stroke began. The drag has two dabs more
        // than a diameter apart, so a level taken at each dab's centre would give two.
        std::vector<Vec2> at;
        const auto h = shared_heights(t1, t2, &at);
        std::vector<double> level;
        double lo = 1e9, hi = -1e9;
        for (const auto& [z0, z1] : h) {
            if (z0 == z1) continue;
            level.push_back(z1);
            lo = std::min(lo, z0);
            hi = std::max(hi, z0);
        }
        ASSERT_GT(level.size(), 20u);
        const auto [low, high] = std::minmax_element(level.begin(), level.end());
        EXPECT_LT(*high - *low, 1e-12);
        EXPECT_GT(hi - lo, 1e-3);  // the dunes were not flat there already
        EXPECT_GT(*low, lo);
        EXPECT_LT(*low, hi);
    }
    {
        // The foot stroke (extrusion on, as the panel's default) cuts its print and keeps
        // the volume within 1 % of what it displaced. The displaced volume is measured by
        // sampling both surfaces, independently of the tools' own accounting.
        const Rect d = t3.domain();
        constexpr int kN = 500;
        const double cell = d.width() * d.height() / (kN * kN);
        double cut = 0.0;
        for (int j = 0; j < kN; ++j) {
            for (int i = 0; i < kN; ++i) {
                const Vec2 p{d.min.x + (i + 0.5) * d.width() / kN,
                             d.min.y + (j + 0.5) * d.height() / kN};
                cut += std::max(0.0, *t2.height_at(p) - *t3.height_at(p)) * cell;
            }
        }
        // A print of the 0.26 m x 0.1 m sole 1 cm deep displaces well over 1e-4 m³.
        EXPECT_GT(cut, 1e-4) << "cut " << cut << " m^3";
        EXPECT_LE(std::abs(t3.volume() - t2.volume()), 0.01 * cut)
            << "net " << t3.volume() - t2.volume() << " m^3, cut " << cut;
        EXPECT_GT(t3.constrained_edge_count(), 0u);  // the print's rims are constrained edges
        std::printf("[ info     ] foot stroke cut %.3g m^3\n", cut);
    }
    {
        // A Weather stroke across the dunes: where it reached, the crests wore and their sand
        // landed lower down, so the volume stays (a sampled cut against the exact volumes)
        // and the highest point there came down; it reached a stroke's width, not the
        // terrain (the drag's window coordinates are not the terrain's, so the reached
        // region is found from the surfaces).
        const Rect d = t4.domain();
        constexpr int kN = 400;
        const double cell = d.width() * d.height() / (kN * kN);
        double cut = 0.0, top_before = -1e9, top_after = -1e9;
        int reached = 0;
        for (int j = 0; j < kN; ++j) {
            for (int i = 0; i < kN; ++i) {
                const Vec2 p{d.min.x + (i + 0.5) * d.width() / kN,
                             d.min.y + (j + 0.5) * d.height() / kN};
                const double z3 = *t3.height_at(p), z4 = *t4.height_at(p);
                cut += std::max(0.0, z3 - z4) * cell;
                if (std::abs(z4 - z3) <= 1e-12) continue;
                ++reached;
                top_before = std::max(top_before, z3);
                top_after = std::max(top_after, z4);
            }
        }
        EXPECT_GT(cut, 1e-7) << "cut " << cut << " m^3";
        EXPECT_LE(std::abs(t4.volume() - t3.volume()), 1e-3 * cut)
            << "net " << t4.volume() - t3.volume() << " m^3, cut " << cut;
        EXPECT_LT(top_after, top_before);
        EXPECT_GT(reached, 100);
        EXPECT_LT(reached, kN * kN / 10);
        std::printf("[ info     ] weather stroke moved %.3g m^3, net %.3g m^3\n", cut,
                    t4.volume() - t3.volume());
    }
}

// The Erosion panel's state line is true: "paused" while paused (it said "sliding, 40800
// active" on the untouched sandbox, and counts above the vertex count on the GPU), "at rest"
// once the sand rests, and while sand slides a count of distinct vertices, never more than
// the terrain has. The stats report the line the panel shows.
TEST_F(EditorXvfb, TheErosionStatusLineIsTrue) {
    const EditorRun paused = run_editor("erosion-paused", kFlat);
    ASSERT_EQ(paused.exit_code, 0) << paused.log;
    EXPECT_EQ(paused.stats.at("erosion_status").get<std::string>(), "paused");

    const EditorRun rest = run_editor(
        "erosion-rest", R"([{"op": "set", "erosion": true}, {"op": "wait", "frames": 80}])");
    ASSERT_EQ(rest.exit_code, 0) << rest.log;
    EXPECT_EQ(rest.stats.at("erosion_status").get<std::string>(), "at rest");

    for (const char* physics : {"cpu", "gpu"}) {
        const EditorRun r =
            run_editor(std::string("erosion-sliding-") + physics,
                       std::string(R"([{"op": "set", "erosion": false, "physics": ")") + physics +
                           R"(", "pour_volume": 0.0002}, {"op": "tool", "name": "Pour"},
                {"op": "click", "at": [0.6, 0.5]}, {"op": "set", "erosion": true,
                "steps": 1}])",
                       "--frames 2");
        ASSERT_EQ(r.exit_code, 0) << r.log;
        const std::string status = r.stats.at("erosion_status").get<std::string>();
        unsigned long active = 0;
        ASSERT_EQ(std::sscanf(status.c_str(), "sliding, %lu active", &active), 1)
            << physics << ": " << status;
        EXPECT_GT(active, 0u);
        EXPECT_LE(active, r.stats.at("vertices").get<unsigned long>()) << physics;
    }
}

TEST_F(EditorXvfb, EveryPanelControlFitsInsideItsPanel) {
    // The panels have a fixed width: a control or label that does not fit is cut off at the
    // edge (the Import and Export buttons and the Settle margin label once were). Every panel
    // open, every tool picked in turn (each shows its own controls) and the haptic loop
    // connected (its live lines), on the 1 m sandbox and on a 100 m terrain, whose sliders
    // show other units. The editor measures how far each section's controls reach past its
    // window's edge (layout_probe.hpp); it must be nowhere. The status line (here "nothing to
    // undo", and on the 100 m terrain the scaling notice before it) must be on screen at the
    // smaller window sizes too, where the panel is taller than the window and scrolls: it
    // once was the panel's last line, below the fold at 1280 x 720.
    std::string ops = R"([{"op": "set", "erosion": false}, {"op": "panels", "open": true},
        {"op": "key", "key": "z", "ctrl": true}, {"op": "wait", "frames": 1})";
    for (const editor::ToolEntry& t : editor::kTools)
        ops += std::string(R"(, {"op": "tool", "name": ")") + t.label +
               R"("}, {"op": "wait", "frames": 1})";
    ops += R"(, {"op": "tool", "name": "Box"}, {"op": "haptics", "connect": true},
        {"op": "wait", "frames": 3}])";
    const fs::path large = kWork / "layout-100m.sandtin";
    // unit_square_points spans the unit square: scaled to the 100 m terrain. An elevation model
    // 1 000 m above the datum: the Stats line "volume 10000000.000 m3" is longer than the line
    // the Stats window's width was once made for, and was cut off.
    std::vector<Vec2> points = unit_square_points(400, 7);
    for (Vec2& p : points)
        p = p * 100.0;
    save_flat_scene(large, 100.0, points, 1000.0);
    for (const std::string& scene : {std::string(), large.string()}) {
        for (const std::string size : {"1280x720", "1024x640"}) {
            const std::string run = (scene.empty() ? "layout-sandbox-" : "layout-100m-") + size;
            const EditorRun r = run_editor(run, ops, scene + " --size " + size);
            ASSERT_EQ(r.exit_code, 0) << r.log;
            EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
            const nlohmann::json& overflow = r.stats.at("layout_overflow_px");
            for (const char* section :
                 {"File", "Tools", "Materials", "Erosion", "Haptics", "Stats"}) {
                ASSERT_TRUE(overflow.contains(section))
                    << section << " was never drawn: " << overflow;
                EXPECT_EQ(overflow.at(section).get<double>(), 0.0)
                    << section << " reaches past its panel's edge in " << run;
            }
            const nlohmann::json& hidden = r.stats.at("layout_hidden_px");
            ASSERT_TRUE(hidden.contains("status")) << "no status line was drawn in " << run;
            EXPECT_EQ(hidden.at("status").get<double>(), 0.0)
                << "the status line is (partly) out of sight in " << run;
        }
    }
}

// Data first: the scene is saved before the screenshot is written, and one output's failure
// does not skip the other; each failure is reported and the run exits 1. (The screenshot used
// to be written first, and a bad screenshot path lost the sculpting it was to save.)
TEST_F(EditorXvfb, ABadScreenshotPathStillSavesTheScene) {
    const fs::path saved = kWork / "bad-shot-saved.sandtin";
    const fs::path missing = kWork / "no-such-folder";
    fs::remove(saved);
    const EditorRun r = run_editor(
        "bad-shot", kStroke,
        "--save-after " + saved.string() + " --screenshot " + (missing / "s.png").string());
    EXPECT_EQ(r.exit_code, 1) << r.log;
    EXPECT_NE(r.log.find("cannot write the screenshot"), std::string::npos) << r.log;
    ASSERT_TRUE(fs::exists(saved)) << "the bad screenshot path lost the scene: " << r.log;
    const Tin t = Tin::from_snapshot(load_session(saved).terrain);
    EXPECT_GT(t.constrained_edge_count(), 0u) << "the saved scene lacks the stroke";

    const EditorRun both = run_editor("bad-shot-and-save", kStroke,
                                      "--save-after " + (missing / "x.sandtin").string() +
                                          " --screenshot " + (missing / "s.png").string());
    EXPECT_EQ(both.exit_code, 1) << both.log;
    EXPECT_NE(both.log.find("cannot save the scene"), std::string::npos) << both.log;
    EXPECT_NE(both.log.find("cannot write the screenshot"), std::string::npos) << both.log;
}

// A session is never written under another format's name (.png, .obj, .json, ...), by the
// editor's Save and Ctrl+S (App::save, here through the script's "save" op) or by
// --save-after (refused before the run, as `sandtin` refuses such an -o), with the CLI's
// words. The editor used to write a session file named out.png.
TEST_F(EditorXvfb, ASessionIsNeverSavedUnderAnotherFormatsName) {
    const fs::path png = kWork / "looks-like.png";
    fs::remove(png);
    const EditorRun save_op = run_editor(
        "save-as-png", then(kFlat, R"({"op": "save", "path": ")" + png.string() + R"("})"));
    EXPECT_EQ(save_op.exit_code, 1) << save_op.log;
    EXPECT_NE(save_op.log.find("not as .png; name it .sandtin"), std::string::npos) << save_op.log;
    EXPECT_FALSE(fs::exists(png));
    const EditorRun after = run_editor("save-after-png", kFlat, "--save-after " + png.string());
    EXPECT_EQ(after.exit_code, 2) << after.log;
    EXPECT_NE(after.log.find("not as .png; name it .sandtin"), std::string::npos) << after.log;
    EXPECT_FALSE(fs::exists(png));
}

// The headless example run.sh prints (when there is no display) works: its script exists and
// runs. It once named docs/scripts/stroke.json, which does not exist.
TEST_F(EditorXvfb, TheHeadlessExampleThatRunShPrintsWorks) {
    const fs::path source(SANDTIN_SOURCE_DIR);
    std::ifstream run_sh(source / "run.sh");
    ASSERT_TRUE(run_sh) << "no run.sh in " << source;
    const std::string text{std::istreambuf_iterator<char>(run_sh), {}};
    const std::size_t at = text.find("--script ");
    ASSERT_NE(at, std::string::npos) << "run.sh shows no --script example";
    const std::size_t from = at + std::string("--script ").size();
    const fs::path script = source / text.substr(from, text.find(' ', from) - from);
    ASSERT_TRUE(fs::exists(script)) << "run.sh suggests " << script << ", which does not exist";
    std::ifstream in(script);
    const nlohmann::json ops = nlohmann::json::parse(in).at("ops");
    const EditorRun r = run_editor("run-sh-example", ops.dump(),
                                   (source / "assets/scenes/default.sandtin").string());
    EXPECT_EQ(r.exit_code, 0) << r.log;
}

TEST_F(EditorXvfb, BadScriptsAndScenesFailWithAClearMessage) {
    const EditorRun r = run_editor("bad-op", R"([{"op": "explode"}])");
    EXPECT_EQ(r.exit_code, 1) << r.log;
    EXPECT_NE(r.log.find("unknown op 'explode'"), std::string::npos) << r.log;
    const EditorRun p = run_editor("bad-physics", R"([{"op": "set", "physics": "tpu"}])");
    EXPECT_EQ(p.exit_code, 1) << p.log;
    EXPECT_NE(p.log.find("physics must be auto, cpu or gpu"), std::string::npos) << p.log;
    const EditorRun f = run_editor("bad-falloff", R"([{"op": "set", "falloff": "cubic"}])");
    EXPECT_EQ(f.exit_code, 1) << f.log;
    EXPECT_NE(f.log.find("falloff must be constant, linear, smooth or gaussian, not 'cubic'"),
              std::string::npos)
        << f.log;
    const EditorRun s = run_editor("bad-scene", kFlat, (kWork / "missing.sandtin").string());
    EXPECT_EQ(s.exit_code, 1) << s.log;
    EXPECT_NE(s.log.find("does not exist"), std::string::npos) << s.log;
    // An option whose value is missing, followed by another option: a usage error naming it,
    // not "--frames" taken as a path and "2" as the scene.
    const EditorRun o = run_editor("bad-option", kFlat, "--save-after --frames 2");
    EXPECT_EQ(o.exit_code, 2) << o.log;
    EXPECT_NE(o.log.find("option --save-after needs a value"), std::string::npos) << o.log;
}

}  // namespace
}  // namespace sandtin
