// Water in the editor (issue 40, item 7), through the real editor under Xvfb: the Water tool's
// nozzle gives what its rate says over the frames it is held (a scripted frame counts 1/60 s)
// and the water spreads from it; the Water panel's rain adds its rate over the terrain's
// area; the water is drawn (blue-green over the yellow sand where it stands); it is saved with
// the scene, and Ctrl+Z takes it away again.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "editor_harness.hpp"
#include "formats/png_image.hpp"
#include "io/session_file.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

std::string save_op(const fs::path& p) {
    return R"({"op": "save", "path": ")" + p.string() + R"("})";
}

/// m³ of water a saved scene holds.
double water_in(const fs::path& scene) {
    return test::water_volume(Tin::from_snapshot(load_session(scene).terrain));
}

std::size_t wet_vertices_in(const fs::path& scene) {
    const VertexArrays& va = load_session(scene).terrain.vertices;
    std::size_t n = 0;
    for (std::size_t v = 0; v < va.size(); ++v)
        n += va.alive[v] && va.water_depth[v] > 0.0 ? 1 : 0;
    return n;
}

TEST_F(EditorXvfb, TheWaterToolPoursWhatItsRateSaysAndTheWaterIsDrawnAndSaved) {
    const fs::path scene = kWork / "water-nozzle.sandtin";
    const fs::path shot = kWork / "water-nozzle.png";
    const fs::path dry_shot = kWork / "water-nozzle-dry.png";
    // 0.2 L/s held for 30 scripted frames: 0.1 L, give or take the frames of the ops that
    // start and end it (each op's frame runs the water too). The mouse then leaves the terrain,
    // so the tool's cursor (a cyan ring where the nozzle was) is not in the picture.
    const std::string away = R"({"op": "move", "at": [0.97, 0.9]})";
    const std::string ops = R"([{"op": "set", "erosion": false, "water_nozzle": 2e-4},
        {"op": "tool", "name": "Water"},
        {"op": "press", "at": [0.5, 0.5]}, {"op": "wait", "frames": 30}, {"op": "release"}, )" +
                            away + R"(, {"op": "wait", "frames": 10}, )" + save_op(scene) + "]";
    const EditorRun r = run_editor(
        "water-nozzle", ops, fresh_settings("water-nozzle") + " --screenshot " + shot.string());
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const double frame = 2e-4 / 60.0;
    const double held = water_in(scene);
    EXPECT_GE(held, 1e-4 - 3.0 * frame);
    EXPECT_LE(held, 1e-4 + 3.0 * frame);
    EXPECT_NEAR(r.stats.at("water").at("m3").get<double>(), held, 1e-12);
    EXPECT_GT(wet_vertices_in(scene), 10u);  // it ran from the nozzle's vertex

    // Drawn: the same view without the pour is the oracle. Where the water stands (the middle
    // of the view, where the nozzle was) it turns the yellow sand towards blue-green; the dry
    // sand up the slope beyond it looks as it did. Means over 21 x 21 pixels (the pond is about
    // 150 across): the running water's ripples glint white, which one pixel may catch.
    const EditorRun d =
        run_editor("water-nozzle-dry",
                   R"([{"op": "set", "erosion": false}, {"op": "tool", "name": "Water"}, )" + away +
                       R"(, {"op": "wait", "frames": 2}])",
                   fresh_settings("water-nozzle-dry") + " --screenshot " + dry_shot.string());
    ASSERT_EQ(d.exit_code, 0) << d.log;
    const PngImage wet = read_png(shot), dry = read_png(dry_shot);
    const auto blueness = [](const Rgb& c) { return c.b - c.r; };
    const int cx = int(wet.width / 2), cy = int(wet.height / 2);
    const double shift =
        blueness(mean_pixel(wet, cx, cy, 10)) - blueness(mean_pixel(dry, cx, cy, 10));
    std::printf("[ info     ] the pond's blue - red over the dry sand's: %+.1f\n", shift);
    EXPECT_GT(shift, 15.0) << "the water at the centre is not drawn";
    const int sx = int(wet.width * 62 / 100), sy = int(wet.height * 35 / 100);
    EXPECT_LT(mean_diff(wet, dry, sx - 10, sy - 10, sx + 11, sy + 11), 2.0)
        << "the dry sand up the slope should look as it did";
}

TEST_F(EditorXvfb, TheRainToolRainsOnTheDiscUnderTheCursorWhileHeld) {
    const fs::path scene = kWork / "water-shower.sandtin";
    // 3 600 mm/h (1 mm/s) on a disc of 10 cm, held 30 scripted frames, the water standing
    // still: every wet vertex took the same depth (0.5 mm, give or take the frames of the ops
    // that start and end it), and the wet vertices make a disc of the Size.
    const std::string ops = R"([{"op": "set", "erosion": false, "water_flowing": false,
        "water_shower": 3600, "radius": 0.1},
        {"op": "tool", "name": "Rain"},
        {"op": "press", "at": [0.5, 0.5]}, {"op": "wait", "frames": 30}, {"op": "release"},
        {"op": "wait", "frames": 5}, )" +
                            save_op(scene) + "]";
    const EditorRun r = run_editor("water-shower", ops, fresh_settings("water-shower"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const VertexArrays& va = load_session(scene).terrain.vertices;
    std::vector<Vec2> wet;
    double depth = -1.0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || va.water_depth[v] == 0.0) continue;
        if (depth < 0.0) depth = va.water_depth[v];
        EXPECT_NEAR(va.water_depth[v], depth, 1e-12) << "the shower fell unevenly";
        wet.push_back(va.position[v]);
    }
    ASSERT_GT(wet.size(), 20u);
    const double frame = 1e-3 / 60.0;
    EXPECT_GE(depth, 0.5e-3 - 3.0 * frame);
    EXPECT_LE(depth, 0.5e-3 + 3.0 * frame);
    // The wet vertices lie within a disc of the Size (the press point, in the terrain, is the
    // editor's to find): no two are further apart than its diameter, and they span most of it.
    double widest = 0.0;
    for (const Vec2 p : wet)
        for (const Vec2 q : wet)
            widest = std::max(widest, length(p - q));
    EXPECT_LE(widest, 0.2 + 1e-6) << "rain fell outside the disc";
    EXPECT_GE(widest, 0.16) << "the disc is smaller than the Size";
}

TEST_F(EditorXvfb, TheSpeedOverlayColoursTheRunningWaterAndNothingElse) {
    // The same pour twice, with the Water panel's Speed overlay off and on: the water at the
    // nozzle (the centre of the view) changes colour, the dry sand up the slope does not.
    const auto shot_of = [&](const std::string& name, bool overlay) {
        const fs::path shot = kWork / (name + ".png");
        const std::string ops = R"([{"op": "set", "erosion": false, "water_nozzle": 2e-4,
            "speed_overlay": )" +
                                std::string(overlay ? "true" : "false") +
                                R"(}, {"op": "tool", "name": "Water"},
            {"op": "press", "at": [0.5, 0.5]}, {"op": "wait", "frames": 20}])";
        const EditorRun r =
            run_editor(name, ops, fresh_settings(name) + " --screenshot " + shot.string());
        EXPECT_EQ(r.exit_code, 0) << r.log;
        EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
        return read_png(shot);
    };
    const PngImage plain = shot_of("water-speed-off", false);
    const PngImage speed = shot_of("water-speed-on", true);
    // Summed over a 21 x 21 window: the overlay's colours vary from vertex to vertex.
    const auto differ = [&](int x0, int y0) {
        long sum = 0;
        for (int y = y0 - 10; y <= y0 + 10; ++y) {
            for (int x = x0 - 10; x <= x0 + 10; ++x) {
                const Rgb a = pixel(plain, x, y), b = pixel(speed, x, y);
                sum += std::abs(int(a.r) - int(b.r)) + std::abs(int(a.g) - int(b.g)) +
                       std::abs(int(a.b) - int(b.b));
            }
        }
        return static_cast<double>(sum) / (21.0 * 21.0);
    };
    EXPECT_GT(differ(plain.width / 2, plain.height / 2), 60.0)
        << "the running water is drawn the same with the Speed overlay";
    EXPECT_LE(differ(plain.width * 62 / 100, plain.height * 35 / 100), 6.0)
        << "the overlay coloured dry sand";
}

TEST_F(EditorXvfb, WithErodeOnTheStreamMovesSandAndKeepsItAll) {
    // The Water panel's Erode on, the sand's own sliding off (so that only the water moves
    // it): a stream poured on the sandbox moves sand; Erode off again drops what the water
    // carried, and the sand on the terrain is then exactly the sand there was (the scene is
    // saved before and after; heights are saved in double).
    const fs::path before = kWork / "water-erode-before.sandtin";
    const fs::path after = kWork / "water-erode-after.sandtin";
    const std::string ops = R"([{"op": "set", "erosion": false, "water_erode": true,
        "water_nozzle": 3e-4, "sediment_overlay": true}, )" +
                            save_op(before) + R"(, {"op": "tool", "name": "Water"},
        {"op": "press", "at": [0.5, 0.5]}, {"op": "wait", "frames": 40}, {"op": "release"},
        {"op": "set", "water_erode": false}, {"op": "wait", "frames": 2}, )" +
                            save_op(after) + "]";
    const EditorRun r = run_editor("water-erode", ops, fresh_settings("water-erode"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    EXPECT_EQ(r.stats.at("water").at("sand_carried_m3").get<double>(), 0.0);
    const Tin start = Tin::from_snapshot(load_session(before).terrain);
    const Tin end = Tin::from_snapshot(load_session(after).terrain);
    ASSERT_EQ(start.vertices().size(), end.vertices().size()) << "no re-triangulation expected";
    double moved = 0.0;
    for (std::size_t v = 0; v < start.vertices().size(); ++v)
        moved = std::max(moved, std::abs(end.vertices().height[v] - start.vertices().height[v]));
    EXPECT_GT(moved, 1e-5) << "the stream moved no sand";
    EXPECT_NEAR(end.volume(), start.volume(), 1e-12 * start.volume())
        << "sand appeared or vanished";
}

TEST_F(EditorXvfb, RainAddsItsRateOverTheTerrainAndUndoTakesTheWaterAway) {
    const fs::path undone = kWork / "water-rain-undone.sandtin";
    const fs::path rained = kWork / "water-rain.sandtin";
    // 480 mm/h for 30 scripted frames (0.5 s): 1/15 mm over the 1 m sandbox, 6.7e-5 m³, give or
    // take the frames of the ops that start and end it. The shower
    // and the flow after it are one level while the water runs: Ctrl+Z takes it all, Ctrl+Y
    // brings it back (a save closes the level, so the saves come after).
    const std::string ops = R"([{"op": "set", "erosion": false, "rain": 480},
        {"op": "wait", "frames": 30}, {"op": "set", "rain": 0}, {"op": "wait", "frames": 2},
        {"op": "key", "key": "z", "ctrl": true}, {"op": "wait", "frames": 2}, )" +
                            save_op(undone) + R"(, {"op": "key", "key": "y", "ctrl": true},
        {"op": "set", "water_flowing": false}, {"op": "wait", "frames": 2}, )" +
                            save_op(rained) + "]";
    const EditorRun r = run_editor("water-rain", ops, fresh_settings("water-rain"));
    ASSERT_EQ(r.exit_code, 0) << r.log;
    EXPECT_EQ(r.stats.at("validation_messages").get<int>(), 0);
    const double expected = 480e-3 / 3600.0 * 0.5;  // m/s x s x 1 m²
    const double frame = expected / 30.0;
    const double fell = water_in(rained);
    EXPECT_GE(fell, expected - 3.0 * frame);
    EXPECT_LE(fell, expected + 3.0 * frame);
    EXPECT_EQ(water_in(undone), 0.0);
    EXPECT_NEAR(r.stats.at("water").at("m3").get<double>(), fell, 1e-12);
}

}  // namespace
}  // namespace sandtin
