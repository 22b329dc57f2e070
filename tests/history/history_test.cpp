// Undo and redo of strokes, brushes, pours and erosion runs. Oracle: an id-free picture of the
// whole TIN (tin_state.hpp, built from Tin::snapshot()) taken before and after each action; undo
// must give back the exact "before" picture (vertices with every attribute, triangles with their
// constrained edges, constraint polylines with generations) and redo the exact "after" one.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "history/history.hpp"
#include "physics/material.hpp"
#include "physics/sand_physics.hpp"
#include "tin_state.hpp"
#include "tools/brushes.hpp"
#include "tools/sand.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin {
namespace {

using test::capture;
using test::same_state;
using test::TinState;

const Rect kDomain{{0.0, 0.0}, {1.0, 1.0}};

double dunes(Vec2 p) {
    return 0.05 + 0.02 * std::sin(7.0 * p.x) * std::cos(5.0 * p.y) + 0.01 * p.x;
}

Tin dune_terrain(std::size_t points, std::uint64_t seed = 3) {
    return Tin::random_points(kDomain, points, seed, dunes);
}

std::vector<Vec2> arc_path(Vec2 from, Vec2 to, int n) {
    std::vector<Vec2> path;
    for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        path.push_back(lerp(from, to, t) + Vec2{0.0, 0.05 * std::sin(std::numbers::pi * t)});
    }
    return path;
}

void expect_undo_redo(Tin& tin, History& history, const TinState& before, const TinState& after) {
    ASSERT_TRUE(history.can_undo());
    const HistoryStep u = history.undo();
    ASSERT_TRUE(u.done);
    EXPECT_TRUE(u.report.exact());
    EXPECT_TRUE(same_state(capture(tin), before)) << "after undo of " << u.label;
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
    const HistoryStep r = history.redo();
    ASSERT_TRUE(r.done);
    EXPECT_TRUE(r.report.exact());
    EXPECT_TRUE(same_state(capture(tin), after)) << "after redo of " << r.label;
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

TEST(History, StrokeUndoRestoresTheExactTinAndRedoReappliesIt) {
    for (const char* asset : {"circle", "ball", "box", "lambda"}) {
        SCOPED_TRACE(asset);
        Tin tin = dune_terrain(4000);
        History history(tin);
        SculptContext context(kDomain);
        const Tool tool = Tool::build(load_tool_asset(asset));
        StrokeSettings settings;
        settings.depth = 0.01;
        const TinState before = capture(tin);
        apply_stroke(tin, tool, arc_path({0.25, 0.4}, {0.75, 0.6}, 30), settings, context);
        ASSERT_TRUE(history.record("stroke"));
        const TinState after = capture(tin);
        ASSERT_GT(test::triangle_difference(before, after), 0u);
        expect_undo_redo(tin, history, before, after);
    }
}

TEST(History, BrushesPourAndErosionUndoExactly) {
    Tin tin = dune_terrain(3000, 5);
    History history(tin);
    SculptContext context(kDomain);
    SandPhysics physics(tin, MaterialTable::presets());
    physics.run_to_rest(2000);
    history.record("settle");

    std::vector<TinState> states{capture(tin)};
    const BrushKind kinds[] = {BrushKind::Raise, BrushKind::Lower, BrushKind::Smooth,
                               BrushKind::Flatten, BrushKind::PaintMaterial};
    for (BrushKind kind : kinds) {
        BrushSettings b;
        b.kind = kind;
        b.material = 2;
        b.strength = kind == BrushKind::Raise || kind == BrushKind::Lower ? 0.004 : 0.5;
        for (int i = 0; i < 6; ++i)
            apply_brush(tin, {0.3 + 0.05 * i, 0.5}, b, context);
        ASSERT_TRUE(history.record("brush"));
        states.push_back(capture(tin));
    }
    pour_sand(tin, {0.5, 0.5}, 2e-4, PourSettings{0.04}, context);
    ASSERT_TRUE(history.record("pour"));
    states.push_back(capture(tin));
    const PhysicsStepReport erosion = physics.run_to_rest(5000);
    ASSERT_GT(erosion.changed, 0u);
    ASSERT_TRUE(history.record("erosion"));
    states.push_back(capture(tin));

    // Walk all the way back, then all the way forward.
    for (std::size_t i = states.size() - 1; i > 0; --i) {
        const HistoryStep step = history.undo();
        ASSERT_TRUE(step.done);
        EXPECT_TRUE(step.report.exact());
        EXPECT_TRUE(same_state(capture(tin), states[i - 1])) << "undo of " << step.label;
    }
    for (std::size_t i = 1; i < states.size(); ++i) {
        const HistoryStep step = history.redo();
        ASSERT_TRUE(step.done);
        EXPECT_TRUE(same_state(capture(tin), states[i])) << "redo of " << step.label;
    }
    EXPECT_FALSE(history.can_redo());
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(History, WaterOnTheTerrainAndAStrokeThroughItUndoExactly) {
    Tin tin = dune_terrain(3000, 7);
    History history(tin);
    SculptContext context(kDomain);
    const TinState dry = capture(tin);
    // A pond in the middle, as a water operation leaves it (io/script_water.hpp).
    for (std::uint32_t id = 0; id < tin.vertices().size(); ++id) {
        const VertexId v{id};
        if (!tin.is_alive(v)) continue;
        const double r = length(tin.position(v) - Vec2{0.5, 0.5});
        if (r < 0.2) tin.set_water_depth(v, 0.01 * (0.2 - r));
    }
    ASSERT_TRUE(history.record("water"));
    const TinState wet = capture(tin);
    ASSERT_NE(dry.vertices, wet.vertices);
    // A stroke through the pond re-triangulates under the water, which the new vertices take.
    const Tool tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.depth = 0.01;
    apply_stroke(tin, tool, arc_path({0.3, 0.45}, {0.7, 0.55}, 20), settings, context);
    ASSERT_TRUE(history.record("stroke"));
    const TinState stroked = capture(tin);
    expect_undo_redo(tin, history, wet, stroked);
    ASSERT_TRUE(history.undo().done);
    expect_undo_redo(tin, history, dry, wet);
}

TEST(History, BrushOverAStrokeUndoesBothExactly) {
    // The brush refines edges of the stroke's rim, which splits its constraints: the brush's
    // level changes constraints the stroke's level created.
    for (const char* asset : {"circle", "ball"}) {
        SCOPED_TRACE(asset);
        Tin tin = dune_terrain(20000, 12);
        History history(tin);
        SculptContext context(kDomain);
        const TinState s0 = capture(tin);
        const Tool tool = Tool::build(load_tool_asset(asset));
        StrokeSettings settings;
        settings.depth = 0.012;
        apply_stroke(tin, tool, std::vector<Vec2>{{0.3, 0.5}, {0.7, 0.45}}, settings, context);
        ASSERT_TRUE(history.record("stroke"));
        const TinState s1 = capture(tin);
        BrushSettings b;
        b.radius = 0.05;
        for (int i = 0; i < 8; ++i)
            apply_brush(tin, {0.45 + 0.02 * i, 0.48 + 0.01 * i}, b, context);
        ASSERT_TRUE(history.record("brush"));
        const TinState s2 = capture(tin);
        HistoryStep u = history.undo();
        EXPECT_TRUE(u.report.exact());
        EXPECT_TRUE(same_state(capture(tin), s1));
        u = history.undo();
        EXPECT_TRUE(u.report.exact()) << u.report.unrestored.size() << " unrestored";
        EXPECT_TRUE(same_state(capture(tin), s0));
        history.redo();
        history.redo();
        EXPECT_TRUE(same_state(capture(tin), s2));
    }
}

TEST(History, StrokeAcrossTheBorderUndoesExactly) {
    // A stroke across the domain's edge puts rim vertices on the border. Undo takes them out
    // again (Tin::remove_border_vertex: they lie on straight stretches of the border), so the
    // prior state comes back exactly, with no notch left at the edge; redo restores the stroke.
    Tin tin = dune_terrain(4000, 13);
    History history(tin);
    SculptContext context(kDomain);
    const TinState before = capture(tin);
    const Tool tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.depth = 0.01;
    apply_stroke(tin, tool, std::vector<Vec2>{{0.8, 0.5}, {0.99, 0.5}}, settings, context);
    const TinState after = capture(tin);
    // The stroke did put new vertices on the border (else this tests nothing new).
    std::size_t new_on_border = 0;
    for (const auto& entry : after.vertices) {
        const auto [x, y] = entry.first;
        if (before.vertices.count(entry.first) == 0 &&
            (x == 0.0 || x == 1.0 || y == 0.0 || y == 1.0)) {
            ++new_on_border;
        }
    }
    ASSERT_GT(new_on_border, 0u);
    ASSERT_TRUE(history.record("stroke"));
    const HistoryStep u = history.undo();
    ASSERT_TRUE(u.done);
    EXPECT_TRUE(u.report.exact()) << u.report.unrestored.size() << " unrestored";
    EXPECT_TRUE(same_state(capture(tin), before));
    EXPECT_TRUE(tin.check_valid().ok());
    ASSERT_TRUE(history.redo().done);
    EXPECT_TRUE(same_state(capture(tin), after));
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(History, HundredsOfLevelsUndoToTheStart) {
    Tin tin = dune_terrain(2000, 9);
    History history(tin);
    SculptContext context(kDomain);
    const TinState start = capture(tin);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    BrushSettings b;
    b.radius = 0.04;
    constexpr int kLevels = 120;
    for (int i = 0; i < kLevels; ++i) {
        b.kind = i % 3 == 0 ? BrushKind::Lower : BrushKind::Raise;
        apply_brush(tin, {u(rng), u(rng)}, b, context);
        ASSERT_TRUE(history.record("dab"));
    }
    const TinState end = capture(tin);
    EXPECT_EQ(history.undo_levels(), static_cast<std::size_t>(kLevels));
    for (int i = 0; i < kLevels; ++i)
        ASSERT_TRUE(history.undo().done);
    EXPECT_FALSE(history.can_undo());
    EXPECT_TRUE(same_state(capture(tin), start));
    for (int i = 0; i < kLevels; ++i)
        ASSERT_TRUE(history.redo().done);
    EXPECT_TRUE(same_state(capture(tin), end));
}

TEST(History, MemoryIsBoundedByTheEditedRegion) {
    // The same small stroke on a terrain 10 times larger must cost about the same memory, and
    // far less than one copy of the vertex data.
    std::size_t bytes[2] = {};
    const std::size_t sizes[2] = {40000, 400000};
    for (int k = 0; k < 2; ++k) {
        Tin tin = dune_terrain(sizes[k], 4);
        History history(tin);
        SculptContext context(kDomain);
        const Tool tool = Tool::build(load_tool_asset("circle"));
        StrokeSettings settings;
        settings.depth = 0.005;
        apply_stroke(tin, tool, arc_path({0.45, 0.5}, {0.55, 0.5}, 10), settings, context);
        ASSERT_TRUE(history.record("stroke"));
        bytes[k] = history.bytes();
        if (k == 1) {
            EXPECT_LT(bytes[k], tin.vertex_count() * sizeof(VertexRecord) / 10);
        }
    }
    // The stroke inserts its own rim and inner vertices whatever the density; ten times the
    // vertices under the stroke at most ten times the cost; the rest of the terrain nothing.
    EXPECT_LT(bytes[1], 10 * bytes[0]);
}

TEST(History, LimitsDropTheOldestLevels) {
    Tin tin = dune_terrain(1000, 2);
    HistoryLimits limits;
    limits.max_levels = 5;
    History history(tin, limits);
    SculptContext context(kDomain);
    BrushSettings b;
    std::vector<TinState> states{capture(tin)};
    for (int i = 0; i < 8; ++i) {
        apply_brush(tin, {0.2 + 0.08 * i, 0.5}, b, context);
        history.record("dab");
        states.push_back(capture(tin));
    }
    EXPECT_EQ(history.undo_levels(), 5u);
    EXPECT_EQ(history.dropped_levels(), 3u);
    while (history.can_undo())
        history.undo();
    EXPECT_TRUE(same_state(capture(tin), states[3]));

    HistoryLimits tiny;
    tiny.max_bytes = 1;  // every level is over budget; the newest one is kept anyway
    Tin tin2 = dune_terrain(1000, 2);
    History h2(tin2, tiny);
    for (int i = 0; i < 3; ++i) {
        apply_brush(tin2, {0.3 + 0.1 * i, 0.5}, b, context);
        h2.record("dab");
    }
    EXPECT_EQ(h2.undo_levels(), 1u);
}

TEST(History, NewEditAfterUndoClearsRedoAndUnrecordedEditsAreUndoneFirst) {
    Tin tin = dune_terrain(1000, 6);
    History history(tin);
    SculptContext context(kDomain);
    BrushSettings b;
    const TinState s0 = capture(tin);
    apply_brush(tin, {0.3, 0.3}, b, context);
    history.record("a");
    const TinState s1 = capture(tin);
    history.undo();
    EXPECT_TRUE(history.can_redo());
    apply_brush(tin, {0.7, 0.7}, b, context);
    history.record("b");
    EXPECT_FALSE(history.can_redo());
    EXPECT_EQ(history.next_undo_label(), "b");

    // An edit nobody recorded is undone as its own level, before "b".
    apply_brush(tin, {0.5, 0.2}, b, context);
    const HistoryStep step = history.undo();
    EXPECT_EQ(step.label, "edit");
    EXPECT_EQ(history.next_undo_label(), "b");
    history.undo();
    EXPECT_TRUE(same_state(capture(tin), s0));
    EXPECT_FALSE(history.undo().done);
    EXPECT_FALSE(same_state(s0, s1));
}

TEST(History, NothingToRecordAddsNoLevel) {
    Tin tin = dune_terrain(500, 8);
    History history(tin);
    EXPECT_FALSE(history.record("nothing"));
    EXPECT_FALSE(history.undo().done);
    EXPECT_FALSE(history.redo().done);
    EXPECT_EQ(history.bytes(), 0u);
}

}  // namespace
}  // namespace sandtin
