// The renderer's mesh: slopes and normals on an analytic plane, constrained edges against the
// TIN's own edge queries, and incremental updates from the change journal against a second,
// from-scratch build (after strokes, brushes, pours and erosion), plus the upload size of a
// stamp on a large terrain.

#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace sandtin::render
