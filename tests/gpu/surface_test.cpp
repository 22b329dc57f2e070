// GPU normals (smooth and creased) and the height/normal-map bake.

#include <array>
#include <cmath>

#include "gpu/surface_maps.hpp"
#include "gpu_fixture.hpp"
#include "gpu_scenes.hpp"
#include "io/export_maps.hpp"
#include "maps/height_map.hpp"
#include "maps/normal_map.hpp"
#include "maps/vertex_normals.hpp"

namespace sandtin::gpu {
namespace {

using testing::GpuTest;
using testing::kUnitSquare;

double wavy(Vec2 p) {
    return 0.1 + 0.05 * std::sin(9.0 * p.x) * std::cos(7.0 * p.y) + 0.03 * p.y;
}

TEST_F(GpuTest, VertexNormalsMatchTheCpuWithin1e4) {
    Tin tin = Tin::random_points(kUnitSquare, 20000, 31, wavy);
    TinMirror mirror(ctx(), tin);
    mirror.sync();
    SurfaceMaps maps(mirror);
    maps.compute_normals();
    const std::vector<Vec3> gpu = maps.read_vertex_normals();
    const std::vector<Vec3> cpu = vertex_normals(tin);
    double worst = 0.0;
    for (uint32_t v = 0; v < cpu.size(); ++v) {
        if (!tin.is_alive(VertexId{v})) continue;
        worst = std::max({worst, std::abs(gpu[v].x - cpu[v].x), std::abs(gpu[v].y - cpu[v].y),
                          std::abs(gpu[v].z - cpu[v].z)});
    }
    EXPECT_LE(worst, 1e-4);
    // With exaggerated heights too.
    maps.compute_normals(3.0);
    const std::vector<Vec3> gpu3 = maps.read_vertex_normals();
    const std::vector<Vec3> cpu3 = vertex_normals(tin, 3.0);
    for (uint32_t v = 0; v < cpu3.size(); ++v) {
        if (!tin.is_alive(VertexId{v})) continue;
        ASSERT_NEAR(gpu3[v].z, cpu3[v].z, 1e-4) << v;
    }
}

// A wall along a constrained line: a step from 0.1 (x < 0.5) to 0.3 (x > 0.5) across a steep
// band. Corner normals of triangles on either side of the constrained top edge of the wall
// must be the one-sided normals (a crease), not their average; away from constraints corner
// normals equal the smooth vertex normals.
TEST_F(GpuTest, CornerNormalsKeepCreasesAlongConstrainedEdges) {
    Tin tin = Tin::regular_grid(kUnitSquare, 20, 20, [](Vec2 p) {
        return p.x <= 0.5 ? 0.1 : (p.x >= 0.55 ? 0.3 : 0.1 + 4.0 * (p.x - 0.5));
    });
    // Constrain the vertical grid line at x = 0.5 (the foot of the wall).
    std::vector<VertexId> line;
    for (int j = 0; j <= 20; ++j)
        line.push_back(tin.locate({0.5, j / 20.0}).corners[0]);
    for (int j = 0; j <= 20; ++j) {
        const Location l = tin.locate({0.5, j / 20.0});
        ASSERT_EQ(l.kind, Location::Kind::OnVertex);
        for (int c = 0; c < 3; ++c) {
            if (tin.position(l.corners[c]) == Vec2{0.5, j / 20.0}) line[j] = l.corners[c];
        }
    }
    tin.insert_constraint(line, false, 1);
    TinMirror mirror(ctx(), tin);
    mirror.sync();
    SurfaceMaps maps(mirror);
    maps.compute_normals();
    const std::vector<Vec3> corner = maps.read_corner_normals();
    const std::vector<Vec3> smooth = maps.read_vertex_normals();
    int flat_side = 0, wall_side = 0, elsewhere = 0;
    for (uint32_t s = 0; s < tin.slot_capacity(); ++s) {
        const auto t = tin.slot_triangle(s);
        if (!t[0].valid()) continue;
        for (int c = 0; c < 3; ++c) {
            const Vec2 p = tin.position(t[c]);
            const Vec3 n = corner[3 * s + static_cast<uint32_t>(c)];
            const Vec2 centroid =
                (tin.position(t[0]) + tin.position(t[1]) + tin.position(t[2])) / 3.0;
            const bool on_line = std::abs(p.x - 0.5) < 1e-12 && p.y > 1e-9 && p.y < 1 - 1e-9;
            if (on_line && centroid.x < 0.5) {
                // The flat side: exactly up.
                EXPECT_NEAR(n.z, 1.0, 1e-6) << "slot " << s;
                ++flat_side;
            } else if (on_line && centroid.x > 0.5) {
                // The wall side (slope 4 towards +x): normal tilted to -x.
                const double expect_x = -4.0 / std::sqrt(17.0);
                EXPECT_NEAR(n.x, expect_x, 1e-5) << "slot " << s;
                ++wall_side;
            } else if (std::abs(p.x - 0.5) > 0.2) {
                EXPECT_NEAR(n.z, smooth[t[c].value].z, 1e-6);
                ++elsewhere;
            }
        }
    }
    EXPECT_GT(flat_side, 20);
    EXPECT_GT(wall_side, 20);
    EXPECT_GT(elsewhere, 100);
}

TEST_F(GpuTest, BakedMapsMatchAnalyticPlaneAndSphericalCapAndTheCpuBake) {
    // A tilted plane: every normal is exact, heights are exact.
    const double gx = 0.3, gy = -0.2;
    Tin plane =
        Tin::random_points(kUnitSquare, 2000, 3, [&](Vec2 p) { return 0.5 + gx * p.x + gy * p.y; });
    TinMirror m1(ctx(), plane);
    m1.sync();
    SurfaceMaps s1(m1);
    s1.compute_normals();
    const MapGrid grid(kUnitSquare, 64, 48, SampleAt::Centres);
    const BakedMaps b1 = s1.bake(grid);
    const double len = std::sqrt(gx * gx + gy * gy + 1.0);
    double worst_n = 0.0, worst_h = 0.0;
    for (uint32_t r = 0; r < grid.height; ++r) {
        for (uint32_t c = 0; c < grid.width; ++c) {
            const Vec2 p = grid.position(c, r);
            worst_h = std::max(worst_h, std::abs(b1.height.at(c, r) - (0.5 + gx * p.x + gy * p.y)));
            worst_n = std::max({worst_n, std::abs(b1.normal.at(c, r, 0) + gx / len),
                                std::abs(b1.normal.at(c, r, 1) + gy / len),
                                std::abs(b1.normal.at(c, r, 2) - 1.0 / len)});
        }
    }
    EXPECT_LE(worst_h, 1e-6);
    EXPECT_LE(worst_n, 1e-5);

    // A spherical cap z = sqrt(R^2 - r^2) - (R - 0.3), R = 1.5, on a fine mesh: the interpolated
    // normals approach the sphere's (x - cx, y - cy, z + R - 0.3) / R.
    const double R = 1.5;
    auto cap = [&](Vec2 p) {
        const double r2 = (p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5);
        return std::sqrt(R * R - r2) - (R - 0.3);
    };
    Tin sphere = Tin::regular_grid(kUnitSquare, 120, 120, cap);
    TinMirror m2(ctx(), sphere);
    m2.sync();
    SurfaceMaps s2(m2);
    s2.compute_normals();
    const MapGrid grid2(kUnitSquare, 100, 100, SampleAt::Corners);
    const BakedMaps b2 = s2.bake(grid2);
    double worst_cap = 0.0, worst_cap_h = 0.0;
    for (uint32_t r = 0; r < grid2.height; ++r) {
        for (uint32_t c = 0; c < grid2.width; ++c) {
            const Vec2 p = grid2.position(c, r);
            const double z = cap(p);
            const Vec3 n{(p.x - 0.5) / R, (p.y - 0.5) / R, (z + R - 0.3) / R};
            worst_cap = std::max({worst_cap, std::abs(b2.normal.at(c, r, 0) - n.x),
                                  std::abs(b2.normal.at(c, r, 1) - n.y),
                                  std::abs(b2.normal.at(c, r, 2) - n.z)});
            worst_cap_h = std::max(worst_cap_h, std::abs(b2.height.at(c, r) - z));
        }
    }
    // Cell size h = 1/120 on a sphere of radius 1.5: normals within h / R = 5.6e-3 (worst at
    // the domain border, where vertex normals are one-sided), heights within O(h^2 / R).
    EXPECT_LE(worst_cap, 5e-3);
    EXPECT_LE(worst_cap_h, 1e-4);

    // The CPU bake (double) of the same TIN: the GPU agrees to float precision.
    const MapImage cpu_n = bake_normal_map(sphere, grid2);
    const MapImage cpu_h = bake_height_map(sphere, grid2);
    double worst_cpu = 0.0, worst_cpu_h = 0.0;
    for (size_t i = 0; i < cpu_n.values.size(); ++i)
        worst_cpu = std::max(worst_cpu, std::abs(cpu_n.values[i] - b2.normal.values[i]));
    for (size_t i = 0; i < cpu_h.values.size(); ++i)
        worst_cpu_h = std::max(worst_cpu_h, std::abs(cpu_h.values[i] - b2.height.values[i]));
    EXPECT_LE(worst_cpu, 1e-4);
    EXPECT_LE(worst_cpu_h, 1e-5);

    // The GPU maps go through the same exporters as the CPU bakes.
    const std::vector<uint8_t> png = encode_normal_png(b2.normal);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png[2], 'N');
    EXPECT_EQ(png[3], 'G');
    EXPECT_GT(encode_height_exr(b2.height, 1.0 / 99.0).size(), 100u);
}

}  // namespace
}  // namespace sandtin::gpu
