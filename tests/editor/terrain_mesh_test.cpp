// The renderer's mesh: slopes and normals on an analytic plane, constrained edges against the
// TIN's own edge queries, and incremental updates from the change journal against a second,
// from-scratch build (after strokes, brushes, pours and erosion), plus the upload size of a
// stamp on a large terrain.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <span>
#include <vector>

#include "gpu/render/terrain_mesh.hpp"
#include "physics/material.hpp"
#include "physics/sand_physics.hpp"
#include "tin/tin.hpp"
#include "tools/brushes.hpp"
#include "tools/sand.hpp"
#include "tools/stroke.hpp"
#include "tools/tool_json.hpp"

namespace sandtin::render {
namespace {

TEST(TerrainMesh, PlaneAtTheAngleOfReposeCarriesItsTalusSlopeAndNormal) {
    const MaterialTable materials = MaterialTable::presets();
    const double t = materials.at(0).talus_slope(0.0);
    const double gx = t * std::cos(0.5236), gy = t * std::sin(0.5236);  // |grad| = t
    const Tin tin =
        Tin::regular_grid({{0, 0}, {2, 1}}, 8, 4, [&](Vec2 p) { return gx * p.x + gy * p.y; });
    TerrainMesh mesh(materials);
    mesh.rebuild(tin);
    ASSERT_GE(mesh.vertices().size(), tin.vertex_capacity());
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i) {
        const RenderVertex& v = mesh.vertices()[i];
        EXPECT_NEAR(v.overlay[0], t, 1e-6);  // tan(repose), the Slope overlay's yardstick
        EXPECT_NEAR(v.normal[2], 1.0 / std::sqrt(1.0 + t * t), 1e-6);
        EXPECT_NEAR(v.normal[0], -gx / std::sqrt(1.0 + t * t), 1e-6);
        EXPECT_NEAR(static_cast<double>(v.position[0]) + 1.0, tin.position(VertexId{i}).x, 1e-6);
    }
}

TEST(TerrainMesh, WaterSpeedsReachTheWetVerticesTheJournalNames) {
    Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 6, 6);
    TerrainMesh mesh(MaterialTable::presets());
    mesh.rebuild(tin);
    tin.take_changes();
    std::vector<float> speed(tin.vertex_capacity(), 0.25f);
    mesh.set_water_speed(speed);
    // Vertex 3 takes water: it and its ring are recomputed; only wet vertices show a speed.
    tin.set_water_depth(VertexId{3}, 0.01);
    mesh.update(tin, tin.take_changes());
    EXPECT_EQ(mesh.vertices()[3].speed, 0.25f);
    EXPECT_EQ(mesh.vertices()[3].water, 0.01f);
    for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v)
        if (v != 3) {
            EXPECT_EQ(mesh.vertices()[v].speed, 0.0f) << "dry vertex " << v;
        }
    // Ids past the speeds' end (the water has not run since they were born) flow at 0.
    mesh.set_water_speed(std::span<const float>(speed.data(), 2));
    tin.set_water_depth(VertexId{3}, 0.02);
    mesh.update(tin, tin.take_changes());
    EXPECT_EQ(mesh.vertices()[3].speed, 0.0f);
}

TEST(TerrainMesh, ConstrainedEdgesAreTheTinsConstrainedEdges) {
    Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 6, 6);
    const VertexId a = tin.insert_point({0.21, 0.33}, 0.0);
    const VertexId b = tin.insert_point({0.77, 0.61}, 0.0);
    const VertexId c = tin.insert_point({0.3, 0.8}, 0.0);
    tin.insert_constraint(a, b, 1);
    tin.insert_constraint(b, c, 1);
    TerrainMesh mesh(MaterialTable::presets());
    mesh.rebuild(tin);
    const auto& e = mesh.constrained_edges();
    ASSERT_EQ(e.size(), 2 * tin.constrained_edge_count());
    for (std::size_t i = 0; i < e.size(); i += 2)
        EXPECT_TRUE(tin.is_constrained_edge(VertexId{e[i]}, VertexId{e[i + 1]}));
    // Every triangle edge appears once in the wireframe list: E = V + T - 1 (Euler, planar).
    EXPECT_EQ(mesh.all_edges().size() / 2, tin.vertex_count() + tin.triangle_count() - 1);
}

void expect_same(const TerrainMesh& a, const TerrainMesh& b, const Tin& tin) {
    const std::size_t n = std::size_t{tin.slot_capacity()} * 3;
    ASSERT_GE(a.indices().size(), n);
    ASSERT_GE(b.indices().size(), n);
    for (std::size_t i = n; i < a.indices().size(); ++i)
        ASSERT_EQ(a.indices()[i], 0u);
    EXPECT_TRUE(std::equal(a.indices().begin(), a.indices().begin() + static_cast<long>(n),
                           b.indices().begin()));
    EXPECT_EQ(a.constrained_edges(), b.constrained_edges());
    std::size_t differ = 0;
    for (std::uint32_t i = 0; i < tin.vertex_capacity(); ++i) {
        if (!tin.is_alive(VertexId{i})) continue;
        if (std::memcmp(&a.vertices()[i], &b.vertices()[i], sizeof(RenderVertex)) != 0) ++differ;
    }
    EXPECT_EQ(differ, 0u);
}

TEST(TerrainMesh, IncrementalUpdatesEqualAFreshBuild) {
    const Rect domain{{0, 0}, {1, 1}};
    Tin tin = Tin::random_points(domain, 3000, 4, [](Vec2 p) { return 0.05 + 0.02 * p.x * p.y; });
    const MaterialTable materials = MaterialTable::presets();
    TerrainMesh mesh(materials);
    tin.take_changes();
    mesh.rebuild(tin);
    SculptContext context(domain);
    SandPhysics physics(tin, materials);
    const Tool tool = Tool::build(load_tool_asset("ball"));
    StrokeSettings ss;
    ss.depth = 0.01;
    std::vector<std::function<void()>> edits = {
        [&] {
            apply_stroke(tin, tool, std::vector<Vec2>{{0.2, 0.3}, {0.6, 0.5}}, ss, context);
        },
        [&] {
            apply_brush(tin, {0.7, 0.7}, BrushSettings{}, context);
        },
        [&] {
            BrushSettings b;
            b.kind = BrushKind::PaintMaterial;
            b.material = 2;
            apply_brush(tin, {0.4, 0.6}, b, context);
        },
        [&] {
            pour_sand(tin, {0.5, 0.2}, 1e-4, PourSettings{}, context);
        },
        [&] { physics.run_to_rest(3000); },
    };
    for (auto& edit : edits) {
        edit();
        const MeshUpdate u = mesh.update(tin, tin.take_changes());
        EXPECT_FALSE(u.vertices.empty());
        TerrainMesh fresh(materials);
        fresh.rebuild(tin);
        expect_same(mesh, fresh, tin);
    }
}

// A material edit recolours the vertices of the edited materials only (albedo and tan of the
// angle of repose), and the mesh is then what a fresh build with the new table gives.
TEST(TerrainMesh, AMaterialEditRecoloursItsVerticesAsAFreshBuildWithTheNewTable) {
    Tin tin = Tin::random_points({{0, 0}, {2, 1}}, 3000, 12,
                                 [](Vec2 p) { return 0.1 + 0.05 * std::sin(3.0 * p.x) * p.y; });
    const VertexId removed = tin.locate({1.0, 0.5}).corners[0];
    ASSERT_TRUE(tin.remove_vertex(removed, VolumePolicy::Report));  // a dead id among them
    std::vector<std::uint32_t> gravel;                              // live ids, ascending
    for (std::uint32_t id : {5u, 17u, 400u, 1200u})
        if (tin.is_alive(VertexId{id}) && gravel.size() < 3) gravel.push_back(id);
    ASSERT_EQ(gravel.size(), 3u);
    for (std::uint32_t id : gravel) {
        tin.set_material(VertexId{id}, 2);
        tin.set_moisture(VertexId{id}, 0.5f);
    }
    MaterialTable before = MaterialTable::presets();
    TerrainMesh mesh(before);
    mesh.rebuild(tin);
    std::vector<Material> all = before.all();
    all[2].colour[1] = 0.25f;
    all[2].repose_wet += 0.1;
    const MaterialTable after(all);
    const std::vector<std::uint16_t> changed = mesh.set_materials(after);
    ASSERT_EQ(changed, std::vector<std::uint16_t>{2});
    const MeshUpdate u = mesh.recolour(tin, changed);
    EXPECT_FALSE(u.resized);
    std::vector<std::uint32_t> recoloured;
    for (const IdRange& r : u.vertices)
        for (std::uint32_t i = r.begin; i < r.end; ++i)
            recoloured.push_back(i);
    EXPECT_EQ(recoloured, gravel);
    TerrainMesh fresh(after);
    fresh.rebuild(tin);
    expect_same(mesh, fresh, tin);
    // An unchanged table recolours nothing.
    EXPECT_TRUE(mesh.set_materials(after).empty());
}

TEST(TerrainMesh, AStampOnALargeTerrainUploadsATinyFraction) {
    const Rect domain{{0, 0}, {1, 1}};
    Tin tin = Tin::random_points(domain, 200000, 8, [](Vec2 p) { return 0.05 + 0.01 * p.x; });
    TerrainMesh mesh(MaterialTable::presets());
    tin.take_changes();
    const MeshUpdate all = mesh.rebuild(tin);
    SculptContext context(domain);
    const Tool tool = Tool::build(load_tool_asset("circle"));
    stamp(tin, tool, {{0.5, 0.5}, 0.0, 0.04}, context);
    const MeshUpdate u = mesh.update(tin, tin.take_changes());
    EXPECT_GT(u.bytes(), 0u);
    EXPECT_LT(u.bytes(), all.bytes() / 100) << u.bytes() << " of " << all.bytes();
}

TEST(TerrainMesh, ALakesSurfaceIsLevelIntoItsBanksWhichHideItAboveTheWaterline) {
    // A bowl z = |p - c|^2 holding a lake whose surface is at 0.04 m: wet where the bed is
    // below it. Every vertex a water triangle touches must carry the lake's level where the
    // bank rises above it (the bank, drawn first, then hides the surface), and the bed plus its
    // water where it is wet: the level again. Away from the water the surface is the height.
    const double level = 0.04;
    Tin tin = Tin::regular_grid(Rect::from_size(1, 1), 30, 30, [](Vec2 p) {
        return length_squared(p - Vec2{0.5, 0.5});
    });
    for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v) {
        const double h = tin.vertices().height[v];
        if (h < level) tin.set_water_depth(VertexId{v}, level - h);
    }
    TerrainMesh mesh(MaterialTable::presets());
    mesh.rebuild(tin);
    std::vector<std::uint8_t> on_water(tin.vertex_capacity(), 0);
    for (std::uint32_t i : mesh.water_indices())
        on_water[i] = 1;
    int banks = 0;
    for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v) {
        const RenderVertex& r = mesh.vertices()[v];
        const double h = tin.vertices().height[v];
        if (on_water[v]) {
            EXPECT_NEAR(r.surface, level, 1e-6) << "vertex " << v;
            banks += h > level ? 1 : 0;
        } else {
            EXPECT_EQ(r.surface, static_cast<float>(h)) << "vertex " << v;
        }
    }
    EXPECT_GT(banks, 20);  // the lake's rim of dry vertices
}

/// The oracle for the water surface's triangles: every live slot with a wet corner, as sorted
/// corner triples.
std::vector<std::array<std::uint32_t, 3>> wet_slots(const Tin& tin) {
    std::vector<std::array<std::uint32_t, 3>> out;
    const VertexArrays& va = tin.vertices();
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        const auto c = tin.slot_triangle(s);
        if (!c[0].valid()) continue;
        bool wet = false;
        for (VertexId v : c)
            wet = wet || va.water_depth[v.index()] > 0.0;
        if (!wet) continue;
        std::array<std::uint32_t, 3> t{c[0].value, c[1].value, c[2].value};
        std::sort(t.begin(), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// What the mesh draws the water on, as sorted triples (duplicates kept: each must be once).
std::vector<std::array<std::uint32_t, 3>> drawn_wet(const TerrainMesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> out;
    const auto& w = mesh.water_indices();
    EXPECT_EQ(w.size() % 3, 0u);
    for (std::size_t k = 0; k + 2 < w.size(); k += 3) {
        std::array<std::uint32_t, 3> t{w[k], w[k + 1], w[k + 2]};
        std::sort(t.begin(), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(TerrainMesh, TheWaterSurfaceIsEveryTriangleWithAWetCornerOnceThroughEveryKindOfEdit) {
    std::mt19937 rng(40);
    std::uniform_real_distribution<double> u(0.02, 0.98);
    Tin tin =
        Tin::random_points(Rect::from_size(1, 1), 400, 40, [](Vec2 p) { return 0.01 * p.x * p.y; });
    TerrainMesh mesh(MaterialTable::presets());
    mesh.rebuild(tin);
    tin.take_changes();
    EXPECT_TRUE(mesh.water_indices().empty());  // a dry terrain has no water surface
    std::vector<VertexId> live;
    auto refresh_live = [&] {
        live.clear();
        for (std::uint32_t v = 0; v < tin.vertex_capacity(); ++v)
            if (tin.is_alive(VertexId{v})) live.push_back(VertexId{v});
    };
    refresh_live();
    // A pond on a disc, then random flips wet <-> dry, then insertions and removals under the
    // water, each checked against the slots.
    for (VertexId v : live) {
        const Vec2 p = tin.position(v);
        if (length(p - Vec2{0.4, 0.5}) < 0.2) tin.set_water_depth(v, 0.01);
    }
    MeshUpdate up = mesh.update(tin, tin.take_changes());
    EXPECT_TRUE(up.water_changed);
    ASSERT_FALSE(wet_slots(tin).empty());
    EXPECT_EQ(drawn_wet(mesh), wet_slots(tin));
    for (int round = 0; round < 30; ++round) {
        refresh_live();
        for (int k = 0; k < 15; ++k) {
            const VertexId v = live[rng() % live.size()];
            tin.set_water_depth(v, tin.vertices().water_depth[v.index()] > 0.0 ? 0.0 : 0.003);
        }
        if (round % 3 == 1) {
            for (int k = 0; k < 5; ++k)
                tin.insert_point({u(rng), u(rng)}, 0.005);
        }
        if (round % 3 == 2) {
            for (int k = 0; k < 5; ++k)
                tin.remove_vertex(live[rng() % live.size()]);
        }
        mesh.update(tin, tin.take_changes());
        EXPECT_EQ(drawn_wet(mesh), wet_slots(tin)) << "round " << round;
    }
    // Dried out: nothing left to draw, and a rebuild agrees with the updates.
    refresh_live();
    for (VertexId v : live)
        tin.set_water_depth(v, 0.0);
    up = mesh.update(tin, tin.take_changes());
    EXPECT_TRUE(up.water_changed);
    EXPECT_TRUE(mesh.water_indices().empty());
    tin.set_water_depth(live[7], 0.02);
    mesh.update(tin, tin.take_changes());
    const auto updated = drawn_wet(mesh);
    mesh.rebuild(tin);
    EXPECT_EQ(drawn_wet(mesh), updated);
    EXPECT_EQ(updated, wet_slots(tin));
}

}  // namespace
}  // namespace sandtin::render
