// Sculpting and erosion in the editor under Xvfb: the tools, Pour and r_S scale with the
// terrain's size (similarity: the same script 100 times larger gives the same terrain 100
// times larger), Pour and Remove move sand by the gesture and not by the mouse events, an
// opened scene is simplified with the panel's tolerance, eroded ground is simplified once the
// sand rests, an opened scene steeper than repose slides, the brushes do what their names say,
// and the Erosion panel's status line is true. Oracles: the saved sessions read back through
// engine/io, analytic volumes and the physics tests' slope oracles.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "editor_harness.hpp"
#include "editor_settings.hpp"
#include "io/script.hpp"
#include "io/session_file.hpp"
#include "physics/material.hpp"
#include "physics/physics_oracles.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"

namespace sandtin {
namespace {

using namespace editor_test;

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

}  // namespace
}  // namespace sandtin
