// The editor never crashes, bricks itself or loses work (issue 43), tested through the real
// input path: every click, key and drag below is an X event that reaches the editor through
// GLFW and ImGui, as a hand's does, and the prompts are answered with their real buttons.
// Oracles: the same file loaded at start-up (screenshots and saved sessions), the files on
// disk byte for byte, the sliders' documented ranges, and the TIN read back through engine/io.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"
#include "editor_settings.hpp"
#include "io/autosave.hpp"
#include "io/heightmap_import.hpp"
#include "io/scene_materials.hpp"
#include "io/session_file.hpp"
#include "sculpting.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"
#include "tool_palette.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

using namespace editor_test;
using namespace editor;

const fs::path kBayHills = fs::path(SANDTIN_SOURCE_DIR) / "tests/data/bay-hills-terrain-rgb.png";

/// The bay-hills tile (a 511 m elevation model) as a scene, imported as the editor imports it.
fs::path dem_scene() {
    const fs::path path = kWork / "dem.sandtin";
    if (fs::exists(path)) return path;
    ImportResult r = import_heightmap(kBayHills, ImportOptions{});
    Session s;
    s.terrain = r.tin.snapshot();
    fs::create_directories(kWork);
    save_session(path, s);
    return path;
}

double max_height(const Tin& t) {
    double hi = -1e300;
    const VertexArrays& va = t.vertices();
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (va.alive[i]) hi = std::max(hi, va.height[i]);
    }
    return hi;
}

Tin tin_of(const fs::path& scene) {
    return Tin::from_snapshot(load_session(scene).terrain);
}

/// The largest per-pixel channel difference over the terrain's part of the view: right of the
/// panel, below the Stats window, above the bottom edge (the status line sits under the panel).
int max_viewport_diff(const PngImage& a, const PngImage& b) {
    int worst = 0;
    for (std::uint32_t y = 200; y < 710; ++y) {
        for (std::uint32_t x = 340; x < 1270; ++x) {
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(static_cast<int>(a.sample(x, y, c)) -
                                                 static_cast<int>(b.sample(x, y, c))));
        }
    }
    return worst;
}

// A stroke across the view (the terrain, right of the panel), then three frames.
const std::string kDrag =
    R"({"op": "tool", "name": "Ball"},
       {"op": "drag", "path": [[0.5, 0.55], [0.7, 0.5]], "steps": 20},
       {"op": "wait", "frames": 3})";

// ---- 1, 2: the prompts' real buttons ------------------------------------------------------

TEST_F(EditorXvfb, RecoverThroughItsButtonOnTheSandboxAndOnAnElevationModel) {
    const fs::path sandbox = kWork / "recover-sandbox.sandtin";
    ASSERT_EQ(
        run_editor("recover-sandbox-base", kFlat, "--save-after " + sandbox.string()).exit_code, 0);
    for (const fs::path& scene : {sandbox, dem_scene()}) {
        const fs::path copy = kWork / ("recover-" + scene.stem().string() + ".sandtin");
        if (copy != scene) fs::copy_file(scene, copy, fs::copy_options::overwrite_existing);
        // An autosave newer than the scene: one vertex near a corner raised (far from the
        // stroke that follows).
        Session edited = load_session(copy);
        const Tin t = Tin::from_snapshot(edited.terrain);
        const Rect d = t.domain();
        std::size_t raised = 0;
        double best = 1e300;
        for (std::size_t i = 0; i < edited.terrain.vertices.alive.size(); ++i) {
            if (!edited.terrain.vertices.alive[i]) continue;
            const Vec2 p = edited.terrain.vertices.position[i];
            const double dist =
                std::hypot(p.x - (d.min.x + 0.1 * d.width()), p.y - (d.min.y + 0.1 * d.height()));
            if (dist < best) best = dist, raised = i;
        }
        const double bump = 0.02 * d.width();
        edited.terrain.vertices.height[raised] += bump;
        write_autosave(copy, edited);
        ASSERT_TRUE(find_autosave(copy)->offer_recovery());

        const fs::path after = kWork / ("recovered-" + scene.stem().string() + ".sandtin");
        const EditorRun r = run_editor(
            "recover-button-" + scene.stem().string(),
            R"([{"op": "wait", "frames": 2}, {"op": "recovery", "choice": "recover"}, )" + kDrag +
                "]",
            copy.string() + " --save-after " + after.string() + fresh_settings("recover"));
        ASSERT_EQ(r.exit_code, 0) << scene << ": " << r.log;
        EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
        // The autosave's terrain, with the stroke on it: the raised vertex is there.
        const Tin got = tin_of(after);
        EXPECT_NEAR(*got.height_at(edited.terrain.vertices.position[raised]),
                    edited.terrain.vertices.height[raised], 1e-9 * d.width())
            << scene;
        EXPECT_GT(surface_difference(got, Tin::from_snapshot(edited.terrain)), 0.0)
            << "the stroke after the recovery did nothing on " << scene;
    }
}

// An autosave is offered however its scene is opened: here through the File panel's Open (the
// recent list and a drop take the same path), not only when the scene is named on the command
// line. Oracle: the autosave's raised vertex in what the editor then saves.
TEST_F(EditorXvfb, OpeningASceneFromThePanelOffersItsAutosave) {
    const fs::path scene = kWork / "recover-open.sandtin";
    save_flat_scene(scene, 1.0, unit_square_points(2000, 91), 0.05);
    const auto [edited, raised] = write_autosave_raising_a_vertex(scene, 0.02);
    ASSERT_TRUE(find_autosave(scene)->offer_recovery());
    const fs::path after = kWork / "recover-open-after.sandtin";
    const EditorRun r = run_editor(
        "recover-open",
        then(kFlat, R"({"op": "set", "scene_path": ")" + scene.string() +
                        R"("}, {"op": "click", "widget": "Open"}, {"op": "wait", "frames": 3},
                        {"op": "recovery", "choice": "recover"}, {"op": "wait", "frames": 2})"),
        "--save-after " + after.string() + fresh_settings("recover-open"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const Tin got = tin_of(after);
    EXPECT_NEAR(*got.height_at(edited.terrain.vertices.position[raised]),
                edited.terrain.vertices.height[raised], 1e-12);
}

TEST_F(EditorXvfb, DiscardAndNewAndSaveAndNewThroughTheirButtons) {
    const fs::path fresh = kWork / "buttons-fresh.sandtin";
    ASSERT_EQ(run_editor("buttons-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const Tin sandbox = tin_of(fresh);

    // On the untitled sandbox: a stroke, New, "Discard and New": a new sandbox.
    const fs::path discarded = kWork / "buttons-discarded.sandtin";
    const EditorRun d =
        run_editor("buttons-discard", "[" + kDrag + R"(, {"op": "click", "widget": "New"},
                           {"op": "discard", "choice": "discard"}, {"op": "wait", "frames": 2}])",
                   "--save-after " + discarded.string() + fresh_settings("buttons"));
    ASSERT_EQ(d.exit_code, 0) << d.log;
    EXPECT_EQ(d.stats.at("validation_messages").get<int>(), 0);
    EXPECT_LT(surface_difference(tin_of(discarded), sandbox), 1e-12);

    // "Save and New": the stroke is written to the Scene field's path, then a new sandbox.
    const fs::path saved = kWork / "buttons-saved.sandtin", after = kWork / "buttons-after.sandtin";
    fs::remove(saved);
    const EditorRun s =
        run_editor("buttons-save",
                   R"([{"op": "set", "scene_path": ")" + saved.string() + R"("}, )" + kDrag +
                       R"(, {"op": "click", "widget": "New"}, {"op": "discard", "choice": "save"},
               {"op": "wait", "frames": 2}])",
                   "--save-after " + after.string() + fresh_settings("buttons"));
    ASSERT_EQ(s.exit_code, 0) << s.log;
    EXPECT_EQ(s.stats.at("validation_messages").get<int>(), 0);
    ASSERT_TRUE(fs::exists(saved));
    EXPECT_GT(surface_difference(tin_of(saved), sandbox), 0.005) << "the stroke was not saved";
    EXPECT_LT(surface_difference(tin_of(after), sandbox), 1e-12);

    // On an imported elevation model (untitled until saved): a stroke, New, Discard.
    const fs::path dem_after = kWork / "buttons-dem.sandtin";
    const EditorRun m = run_editor(
        "buttons-dem",
        R"([{"op": "set", "import_path": ")" + kBayHills.string() + R"("},
            {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 2}, )" +
            kDrag + R"(, {"op": "click", "widget": "New"}, {"op": "discard", "choice": "discard"},
               {"op": "wait", "frames": 2}])",
        "--save-after " + dem_after.string() + fresh_settings("buttons-dem"));
    ASSERT_EQ(m.exit_code, 0) << m.log;
    EXPECT_EQ(m.stats.at("validation_messages").get<int>(), 0);
    EXPECT_LT(surface_difference(tin_of(dem_after), sandbox), 1e-12);
}

// ---- 7: what the viewport shows after Open and Import -------------------------------------

TEST_F(EditorXvfb, OpenAndImportInARunningSessionDrawWhatStartUpDraws) {
    const fs::path dem = dem_scene();
    // Opened in a running session (after the sandbox) and loaded at start-up; a stroke on each.
    const fs::path at_start = kWork / "view-start.png", opened = kWork / "view-open.png";
    const fs::path start_scene = kWork / "view-start.sandtin",
                   open_scene = kWork / "view-open.sandtin";
    const EditorRun a =
        run_editor("view-start", "[" + kDrag + "]",
                   dem.string() + " --frames 2 --screenshot " + at_start.string() +
                       " --save-after " + start_scene.string() + fresh_settings("view-start"));
    const EditorRun b = run_editor(
        "view-open",
        R"([{"op": "wait", "frames": 2}, {"op": "set", "scene_path": ")" + dem.string() +
            R"("}, {"op": "click", "widget": "Open"}, {"op": "wait", "frames": 2}, )" + kDrag + "]",
        "--frames 2 --screenshot " + opened.string() + " --save-after " + open_scene.string() +
            fresh_settings("view-open"));
    ASSERT_EQ(a.exit_code, 0) << a.log;
    ASSERT_EQ(b.exit_code, 0) << b.log;
    EXPECT_EQ(b.stats.at("validation_messages").get<int>(), 0);
    // The same terrain (the same stroke on the same file)...
    EXPECT_LT(surface_difference(tin_of(start_scene), tin_of(open_scene)), 1e-9);
    // ...drawn the same: the mesh, its normals and the baked normal map.
    EXPECT_LE(max_viewport_diff(read_png(at_start), read_png(opened)), 2);

    // Imported in a running session, saved, and that file loaded at start-up.
    const fs::path imported = kWork / "view-imported.sandtin";
    const fs::path import_png = kWork / "view-import.png", reload_png = kWork / "view-reload.png";
    fs::remove(imported);
    const EditorRun c = run_editor(
        "view-import",
        R"([{"op": "wait", "frames": 2}, {"op": "set", "import_path": ")" + kBayHills.string() +
            R"("}, {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 2},
            {"op": "save", "path": ")" +
            imported.string() + R"("}, )" + kDrag + "]",
        "--frames 2 --screenshot " + import_png.string() + fresh_settings("view-import"));
    ASSERT_EQ(c.exit_code, 0) << c.log;
    const EditorRun e = run_editor("view-reload", "[" + kDrag + "]",
                                   imported.string() + " --frames 2 --screenshot " +
                                       reload_png.string() + fresh_settings("view-reload"));
    ASSERT_EQ(e.exit_code, 0) << e.log;
    EXPECT_LE(max_viewport_diff(read_png(import_png), read_png(reload_png)), 2);
}

// ---- 3: typed values and the settings file ------------------------------------------------

// Every slider, through Ctrl+click and the keyboard, as ImGui lets an artist type `text`: far
// below its range or far above it. Each must end at its range's end, and the editor must go on
// sculpting. A window tall enough for every panel at once. (Two tests, one editor run each, so
// that ctest runs them side by side: together they took 55-79 s of one core.)
void check_typed_values_are_clamped(const char* text) {
    struct Slider {
        const char* widget;
        const char* tool;  ///< the tool that shows it ("" : any)
        const char* stat;  ///< its setting in the stats ("" : checked otherwise)
        SettingRange range;
    };
    const Slider sliders[] = {
        {"Size", "Circle", "tool_radius", kToolRadiusRange},
        {"Depth", "Circle", "tool_depth", kToolDepthRange},
        {"Spacing", "Circle", "stroke_spacing_ratio", kStrokeSpacingRange},
        {"Orientation", "Circle", "tool_angle", kToolAngleRange},
        {"Pour", "Pour", "pour_volume", kPourVolumeRange},
        {"Height", "Raise", "brush_strength", kBrushStrengthRange},
        {"Strength", "Smooth", "brush_blend", kBrushBlendRange},
        {"Steps/frame", "", "erosion_steps", kErosionStepsRange},
        {"r_S", "", "relocation_radius", kRelocationRadiusRange},
        {"Settle margin", "", "settle_margin", kSettleMarginRange},
        {"Simplify", "", "simplify_tolerance", kSimplifyToleranceRange},
        {"Contrast", "", "contrast", kContrastRange},
        {"Repose dry", "", "", {}},
        {"Repose moist", "", "", {}},
        {"Paint moisture", "", "", {}},
        {"Loop", "", "", {}},
    };
    const auto type_into = [](const char* widget, const char* typed) {
        return std::string(R"({"op": "click", "widget": ")") + widget +
               R"(", "ctrl": true}, {"op": "wait", "frames": 1}, {"op": "type", "text": ")" +
               typed + R"("}, {"op": "key", "key": "enter"}, {"op": "wait", "frames": 1})";
    };
    // Files of their own: the two tests run side by side.
    const std::string tag = text[0] == '-' ? "low" : "high";
    const fs::path scene = kWork / ("typed-" + tag + ".sandtin");
    // A small flat terrain: every frame is cheap, and the stroke at the end has sand to cut.
    const fs::path small = kWork / ("typed-in-" + tag + ".sandtin");
    save_flat_scene(small, 1.0, unit_square_points(800, 5), 0.05);
    // Erosion off: a 10 degree repose and a 1 mm r_S (the low ends) would otherwise refine
    // the whole sandbox as it slides, which is not what this test is about.
    std::string ops = R"([{"op": "set", "erosion": false},
                              {"op": "panels", "open": true}, {"op": "wait", "frames": 2},
                              {"op": "click", "widget": "Follow path"}, )";
    for (const Slider& s : sliders) {
        if (*s.tool != '\0') ops += std::string(R"({"op": "tool", "name": ")") + s.tool + R"("}, )";
        ops += type_into(s.widget, text) + ", ";
    }
    // Then a stroke with the clamped values: it must cut, not quit. Five centimetres: at the low
    // ends (a 5 mm tool stamped every 0.1 mm) that is already 500 stamps.
    ops += R"({"op": "tool", "name": "Circle"},
                  {"op": "drag", "path": [[0.5, 0.5], [0.55, 0.5]], "steps": 10},
                  {"op": "save_settings"}, {"op": "wait", "frames": 2}])";
    const std::string settings = fresh_settings(std::string("typed") + text);
    const EditorRun r =
        run_editor(std::string("typed") + text, ops,
                   small.string() + " --size 1280x1500 --save-after " + scene.string() + settings);
    ASSERT_EQ(r.exit_code, 0) << text << ": " << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const bool low = text[0] == '-';
    const double size = 1.0;  // the 1 m sandbox
    for (const Slider& s : sliders) {
        if (*s.stat == '\0') continue;
        const double got = r.stats.at("settings").at(s.stat).get<double>();
        const double want = low ? s.range.lo_at(size) : s.range.hi_at(size);
        EXPECT_NEAR(got, want, 1e-6 * std::max(1.0, std::abs(want))) << s.widget << " " << text;
    }
    // The material sliders: within their ranges (dry 10-50 degrees, moist up to 70, moisture
    // 0-1), as saved with the scene.
    const Session saved = load_session(scene);
    const Material m = materials_or_presets(saved.metadata_json).all().front();
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    EXPECT_NEAR(m.repose_dry, (low ? 10.0 : 50.0) * kDeg, 1e-4) << text;
    EXPECT_NEAR(m.repose_wet, (low ? 10.0 : 70.0) * kDeg, 1e-4) << text;
    EXPECT_NEAR(m.default_moisture, low ? 0.0 : 1.0, 1e-6) << text;
    // A fresh launch with the settings this session wrote starts and sculpts.
    if (!low) return;
    const EditorRun again = run_editor(std::string("typed-again") + text,
                                       R"([{"op": "tool", "name": "Circle"},
                {"op": "drag", "path": [[0.5, 0.5], [0.55, 0.5]], "steps": 10}])",
                                       settings);
    EXPECT_EQ(again.exit_code, 0) << again.log;
}

// (Digits only: ImGui reads an integer slider's text with %d, which takes "1e9" as 1.)
TEST_F(EditorXvfb, TypedValuesFarBelowTheRangeAreClampedInEverySlider) {
    check_typed_values_are_clamped("-1000");
}

TEST_F(EditorXvfb, TypedValuesFarAboveTheRangeAreClampedInEverySlider) {
    check_typed_values_are_clamped("999999999");
}

TEST_F(EditorXvfb, ASettingsFileWithBadValuesFallsBackFieldByFieldAndSaysSo) {
    const fs::path settings = kWork / "bad-values.settings.json";
    std::ofstream(settings) << R"({"tool_radius": -2, "pour_volume": -5,
        "stroke_spacing_ratio": 0, "brush_blend": -3, "tool_depth": -0.01, "erosion_steps": 0,
        "relocation_radius": 1e9, "contrast": 0.7, "brush_falloff": "cubic"})";
    const fs::path fresh = kWork / "bad-values-fresh.sandtin", after = kWork / "bad-values.sandtin";
    ASSERT_EQ(run_editor("bad-values-fresh", kFlat, "--save-after " + fresh.string()).exit_code, 0);
    const EditorRun r =
        run_editor("bad-values",
                   R"([{"op": "set", "erosion": false}, {"op": "tool", "name": "Circle"},
            {"op": "drag", "path": [[0.5, 0.5], [0.7, 0.5]], "steps": 10}, {"op": "wait", "frames": 2}])",
                   "--settings " + settings.string() + " --save-after " + after.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // The status line named every bad field (its first message); the good one counts.
    const std::string status = r.stats.at("messages").at(0).get<std::string>();
    for (const char* field : {"tool_radius", "pour_volume", "stroke_spacing_ratio", "brush_blend",
                              "tool_depth", "erosion_steps", "relocation_radius", "brush_falloff"})
        EXPECT_NE(status.find(field), std::string::npos) << field << " in: " << status;
    const EditorSettings defaults;
    EXPECT_EQ(r.stats.at("settings").at("tool_radius").get<double>(), defaults.tool_radius);
    EXPECT_EQ(r.stats.at("settings").at("contrast").get<double>(), 0.7);
    // And the stroke cut into the sand.
    EXPECT_GT(surface_difference(tin_of(after), tin_of(fresh)), 0.005);
}

// ---- 4: Import, then Save ------------------------------------------------------------------

TEST_F(EditorXvfb, ImportThenSaveNeverWritesOverTheOpenedSceneOrItsAutosave) {
    const fs::path mine = kWork / "mine.sandtin";
    ASSERT_EQ(run_editor("mine-base", kFlat, "--save-after " + mine.string()).exit_code, 0);
    discard_autosave(mine);
    const std::vector<std::uint8_t> mine_bytes = read_file(mine);
    const fs::path folder = kWork / "import-here";
    fs::remove_all(folder);
    fs::create_directories(folder);
    const fs::path heightmap = folder / "bay.png";
    fs::copy_file(kBayHills, heightmap);

    // Open my scene, sculpt without saving, import a DEM through the File panel, Ctrl+S. (A
    // script's edits go to autosaves only once it asks: its first op.)
    const EditorRun r =
        run_editor("import-save",
                   R"([{"op": "autosave"}, )" + kDrag + R"(, {"op": "set", "import_path": ")" +
                       heightmap.string() + R"("},
           {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 2},
           {"op": "key", "key": "s", "ctrl": true}, {"op": "wait", "frames": 2}])",
                   mine.string() + fresh_settings("import-save"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // My scene is untouched, and the sculpting waits in its autosave.
    EXPECT_EQ(read_file(mine), mine_bytes);
    ASSERT_TRUE(find_autosave(mine).has_value()) << "the unsaved sculpting is gone";
    EXPECT_GT(surface_difference(Tin::from_snapshot(recover_autosave(mine).terrain), tin_of(mine)),
              0.005);
    // The import was saved under a name of its own, beside the heightmap.
    const fs::path named = folder / "bay.sandtin";
    ASSERT_TRUE(fs::exists(named)) << r.stats.dump(2);
    EXPECT_EQ(r.stats.at("scene_path").get<std::string>(), named.string());
    EXPECT_GT(tin_of(named).domain().width(), 500.0);

    // Saving the import over my scene asks first: Cancel writes nothing, Replace writes it.
    for (const char* choice : {"cancel", "replace"}) {
        const EditorRun o =
            run_editor(std::string("import-overwrite-") + choice,
                       R"([{"op": "set", "import_path": ")" + heightmap.string() + R"("},
                {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 2},
                {"op": "set", "scene_path": ")" +
                           mine.string() + R"("},
                {"op": "click", "widget": "Save As"}, {"op": "overwrite", "choice": ")" +
                           choice + R"("}, {"op": "wait", "frames": 2}])",
                       fresh_settings("import-overwrite"));
        ASSERT_EQ(o.exit_code, 0) << o.log;
        if (std::string(choice) == "cancel") {
            EXPECT_EQ(read_file(mine), mine_bytes);
            EXPECT_NE(o.stats.at("status").get<std::string>().find("not saved"), std::string::npos);
        } else {
            EXPECT_GT(tin_of(mine).domain().width(), 500.0);
            EXPECT_FALSE(find_autosave(mine).has_value());
        }
    }
}

// ---- 5: an opened or imported model waits for Run -----------------------------------------

TEST_F(EditorXvfb, AnOpenedOrImportedSceneWaitsForRun) {
    const fs::path dem = dem_scene();
    const Tin original = tin_of(dem);
    const fs::path held = kWork / "held.sandtin", released = kWork / "released.sandtin";
    // Erosion runs (the default setting), but the opened model is not touched until Run.
    const EditorRun r =
        run_editor("held",
                   R"([{"op": "set", "erosion": true}, {"op": "wait", "frames": 10},
            {"op": "save", "path": ")" +
                       held.string() + R"("},
            {"op": "click", "widget": "Run"}, {"op": "wait", "frames": 30}])",
                   dem.string() + " --save-after " + released.string() + fresh_settings("held"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_LT(surface_difference(tin_of(held), original), 1e-9);
    EXPECT_LT(max_height(tin_of(released)), max_height(original) - 0.1)
        << "Run did not let the model settle";

    // Imported: the same.
    const fs::path imported = kWork / "held-import.sandtin";
    const EditorRun i = run_editor(
        "held-import",
        R"([{"op": "set", "erosion": true, "import_path": ")" + kBayHills.string() + R"("},
            {"op": "click", "widget": "Import"}, {"op": "wait", "frames": 10}])",
        "--save-after " + imported.string() + fresh_settings("held-import"));
    ASSERT_EQ(i.exit_code, 0) << i.log;
    EXPECT_NE(i.stats.at("erosion_status").get<std::string>().find("Run"), std::string::npos)
        << i.stats.at("erosion_status");
    ImportResult direct = import_heightmap(kBayHills, ImportOptions{});
    EXPECT_EQ(max_height(tin_of(imported)), max_height(direct.tin));
}

// ---- 9: undo levels -----------------------------------------------------------------------

TEST_F(EditorXvfb, OneStrokeAndItsSettlingAreOneUndoLevelAndUndoKeepsTheErosionRunning) {
    const fs::path first = kWork / "levels-first.sandtin", undone = kWork / "levels-undone.sandtin";
    const std::string stroke = R"({"op": "drag", "path": [[0.5, 0.55], [0.7, 0.5]], "steps": 20},
                                  {"op": "settle", "frames": 1500})";
    // Flat sand 5 cm deep on a coarser terrain than the sandbox (a few thousand points): the
    // strokes' walls slide and settle within seconds. Opened, so Run lets it erode.
    const fs::path scene = kWork / "levels.sandtin";
    save_flat_scene(scene, 1.0, unit_square_points(4000, 11), 0.05);
    const EditorRun r = run_editor(
        "levels",
        R"([{"op": "set", "erosion": true, "steps": 200}, {"op": "click", "widget": "Run"},
            {"op": "tool", "name": "Ball"}, {"op": "set", "radius": 0.05, "depth": 0.02}, )" +
            stroke + R"(, {"op": "save", "path": ")" + first.string() + R"("},
            {"op": "drag", "path": [[0.5, 0.4], [0.7, 0.35]], "steps": 20},
            {"op": "settle", "frames": 1500}, {"op": "key", "key": "z", "ctrl": true},
            {"op": "wait", "frames": 3}])",
        scene.string() + " --save-after " + undone.string() + fresh_settings("levels"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    // Two strokes, each with its settling, were two levels; one undone leaves one.
    EXPECT_EQ(r.stats.at("undo_levels").get<int>(), 1) << r.log;
    EXPECT_TRUE(r.stats.at("erosion_running").get<bool>()) << "undo paused the erosion";
    // And the undo went back to the settled state after the first stroke, not halfway.
    EXPECT_LT(surface_difference(tin_of(undone), tin_of(first)), 1e-9);
    EXPECT_LT(surface_difference(tin_of(first), tin_of(undone)), 1e-9);
}

// ---- 8: scripted input is the mouse's ------------------------------------------------------

TEST_F(EditorXvfb, AScriptedHoverShowsTheTooltipAndAClickOnThePanelNeverSculpts) {
    const fs::path before = kWork / "panel-click-before.sandtin";
    const fs::path after = kWork / "panel-click-after.sandtin";
    // Zoomed in, the terrain lies behind the Stats window too: a click and a drag on its text.
    const EditorRun r =
        run_editor("panel-click",
                   R"([{"op": "set", "erosion": false}, {"op": "camera", "zoom": 4},
            {"op": "save", "path": ")" +
                       before.string() + R"("},
            {"op": "tool", "name": "Circle"}, {"op": "click", "at": [0.85, 0.12]},
            {"op": "drag", "path": [[0.8, 0.14], [0.9, 0.14]], "steps": 5},
            {"op": "hover", "widget": "Size"}, {"op": "wait", "frames": 2}])",
                   "--save-after " + after.string() + fresh_settings("panel-click"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("tooltip").get<std::string>(),
              "Radius of round tools (circle, ball), brushes and the pour");
    EXPECT_LT(surface_difference(tin_of(after), tin_of(before)), 1e-12)
        << "a click on the panel sculpted the terrain behind it";
}

// Item 6: one Foot click with Extrude on (the panel's default) on flat sand puts the sand it
// displaced in a ridge along the sole. It used to heap it in a sunburst, 7-8 radial stripes up
// to ~15 cm long. Oracles: the flat level (what rose is the ridge), the tool's extrusion width
// (nothing rises farther than that from the print's outline, which the cut vertices trace to a
// mesh spacing), and the volume, the same before and after.
TEST_F(EditorXvfb, AFootClickWithExtrudeRaisesItsRidgeOnlyAlongTheSole) {
    constexpr double kLevel = 0.1;
    constexpr int kPoints = 40000;
    const fs::path flat = kWork / "foot-flat.sandtin";
    save_flat_scene(flat, 1.0, unit_square_points(kPoints, 17), kLevel);
    const fs::path printed = kWork / "foot-printed.sandtin";
    const std::string ops = R"([{"op": "set", "erosion": false, "simplify_tolerance": 0},
        {"op": "tool", "name": "Foot"}, {"op": "wait", "frames": 1},
        {"op": "click", "at": [0.5, 0.5]}, {"op": "save", "path": ")" +
                            printed.string() + R"("}])";
    const EditorRun r = run_editor("foot-extrude", ops, flat.string() + fresh_settings("foot"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    const Tin before = Tin::from_snapshot(load_session(flat).terrain);
    const Tin after = Tin::from_snapshot(load_session(printed).terrain);
    EXPECT_NEAR(after.volume(), before.volume(), 1e-9 * before.volume());

    EditorSettings settings;
    settings.tool = *tool_named("Foot");
    settings.extrude = true;
    settings.scene_size = 1.0;
    const double width = build_tool(settings).extrusion_width();
    ASSERT_GT(width, 0.0);
    const double spacing = 1.0 / std::sqrt(static_cast<double>(kPoints));

    std::vector<Vec2> cut, risen;
    double highest = 0.0;
    const VertexArrays& va = after.vertices();
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        if (va.height[i] < kLevel - 1e-6) cut.push_back(va.position[i]);
        if (va.height[i] > kLevel + 1e-6) {
            risen.push_back(va.position[i]);
            highest = std::max(highest, va.height[i] - kLevel);
        }
    }
    ASSERT_GT(cut.size(), 50u) << "the foot printed nothing";
    ASSERT_GT(risen.size(), 50u) << "no ridge: the displaced sand went nowhere";
    std::size_t far = 0;
    double farthest = 0.0;
    for (Vec2 p : risen) {
        double nearest = 1e300;
        for (Vec2 q : cut)
            nearest = std::min(nearest, distance(p, q));
        farthest = std::max(farthest, nearest);
        if (nearest > width + 2.0 * spacing) ++far;
    }
    EXPECT_EQ(far, 0u) << "sand rose up to " << farthest << " m from the print; the ridge is "
                       << width << " m wide";
    // The even ridge of the documented cross-section, (1 - t^2) across the band with t from -1
    // at the outline to 1 at its outer edge, holding the volume the print displaced: the
    // sunburst's spikes stood three times that high. Both integrals are sampled on a grid, the
    // outline traced by the cut vertices; the sole's cut varies along it (4-17 mm at this
    // depth), so the ridge is not even: twice the even height bounds it (1.46 measured).
    constexpr int kN = 250;
    const double cell = 1.0 / (kN * kN);
    double displaced = 0.0, band = 0.0;
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const Vec2 p{(i + 0.5) / kN, (j + 0.5) / kN};
            const double h = after.height_at(p).value_or(kLevel);
            if (h < kLevel) {
                displaced += (kLevel - h) * cell;
                continue;
            }
            double s = 1e300;
            for (Vec2 q : cut)
                s = std::min(s, distance(p, q));
            if (s >= width) continue;
            const double t = 2.0 * s / width - 1.0;
            band += (1.0 - t * t) * cell;
        }
    }
    ASSERT_GT(band, 0.0);
    const double even = displaced / band;
    EXPECT_LE(highest, 2.0 * even) << "a spike: the even ridge is " << even << " m high";
    std::printf(
        "[ info     ] foot ridge: %zu risen vertices, farthest %.4f m (width %.4f m), "
        "highest %.4f m (even ridge %.4f m)\n",
        risen.size(), farthest, width, highest, even);
}

}  // namespace
}  // namespace sandtin
