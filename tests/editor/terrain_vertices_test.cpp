// The renderer's vertex data: one vertex per triangle corner, positions centred on the domain,
// constrained-edge masks equal to the TIN's, and the slope overlay equal to slope/tan(repose)
// on an analytic plane.

#include <gtest/gtest.h>

#include <cmath>

#include "gpu/render/terrain_vertices.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin::render {
namespace {

TEST(TerrainVertices, PlaneAtTheAngleOfReposeHasSlopeRatioOne) {
    const MaterialTable materials = MaterialTable::presets();
    const double t = materials.at(0).talus_slope(0.0);
    // Gradient (t cos 30°, t sin 30°): |grad| = t.
    const double gx = t * std::cos(0.5236), gy = t * std::sin(0.5236);
    Tin tin =
        Tin::regular_grid({{0, 0}, {2, 1}}, 8, 4, [&](Vec2 p) { return gx * p.x + gy * p.y; });
    const auto v = build_terrain_vertices(tin, materials, {});
    ASSERT_EQ(v.size(), tin.triangle_count() * 3);
    for (const TerrainVertex& x : v) {
        EXPECT_NEAR(x.overlay[1], 1.0, 1e-5);
        EXPECT_GE(x.position[0], -1.0f);
        EXPECT_LE(x.position[0], 1.0f);
        EXPECT_NEAR(x.normal[2], 1.0 / std::sqrt(1.0 + t * t), 1e-5);
    }
}

TEST(TerrainVertices, ConstrainedEdgeMasksMatchTheTin) {
    Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 6, 6);
    const VertexId a = tin.insert_point({0.21, 0.33}, 0.0);
    const VertexId b = tin.insert_point({0.77, 0.61}, 0.0);
    tin.insert_constraint(a, b, 1);
    const auto v = build_terrain_vertices(tin, MaterialTable::presets(), {});
    std::size_t flagged = 0;
    for (std::size_t i = 0; i < v.size(); i += 3) {
        const int mask = static_cast<int>(v[i].overlay[0]);
        EXPECT_EQ(v[i + 1].overlay[0], v[i].overlay[0]);
        flagged += static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(mask)));
        // Corner k carries barycentric e_k.
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(v[i + static_cast<std::size_t>(k)].barycentric[k], 1.0f);
    }
    // Every constrained edge is seen from its two triangles.
    EXPECT_EQ(flagged, 2 * tin.constrained_edge_count());
}

}  // namespace
}  // namespace sandtin::render
