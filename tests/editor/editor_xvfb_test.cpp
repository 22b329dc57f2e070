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
#include "io/scene_materials.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
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
