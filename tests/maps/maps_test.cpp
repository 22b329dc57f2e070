// CPU map bakes against brute-force oracles: heights by searching every triangle, normals of
// planes analytically, every sample visited exactly once.

#include <gtest/gtest.h>

#include <cmath>

#include "maps/albedo_map.hpp"
#include "maps/height_map.hpp"
#include "maps/normal_map.hpp"
#include "maps/triangle_raster.hpp"
#include "maps/vertex_normals.hpp"
#include "support/tin_oracles.hpp"

namespace sandtin {
namespace {

double bumpy(Vec2 p) {
    return std::sin(p.x * 1.3) * std::cos(p.y * 0.9) + 0.2 * p.y;
}

TEST(MapGrid, SamplePositions) {
    const Rect d{{1.0, 2.0}, {5.0, 4.0}};
    const MapGrid corners(d, 5, 3, SampleAt::Corners);
    EXPECT_EQ(corners.position(0, 0), (Vec2{1.0, 4.0}));  // north-west
    EXPECT_EQ(corners.position(4, 2), (Vec2{5.0, 2.0}));  // south-east, exactly on the border
    EXPECT_EQ(corners.position(2, 1), (Vec2{3.0, 3.0}));
    const MapGrid centres(d, 4, 2, SampleAt::Centres);
    EXPECT_EQ(centres.position(0, 0), (Vec2{1.5, 3.5}));
    EXPECT_EQ(centres.position(3, 1), (Vec2{4.5, 2.5}));
    for (const MapGrid& g : {corners, centres}) {
        const Vec2 back = g.to_grid(g.position(1, 1));
        EXPECT_NEAR(back.x, 1.0, 1e-12);
        EXPECT_NEAR(back.y, 1.0, 1e-12);
    }
    EXPECT_THROW(MapGrid(d, 1, 3, SampleAt::Corners), std::invalid_argument);
    EXPECT_THROW(MapGrid(d, 0, 3, SampleAt::Centres), std::invalid_argument);
    EXPECT_THROW(MapGrid(Rect{{0, 0}, {0, 1}}, 4, 4, SampleAt::Centres), std::invalid_argument);
    EXPECT_THROW(MapGrid(d, 1u << 15, 1u << 14, SampleAt::Centres), std::invalid_argument);
}

TEST(MapBake, EverySampleIsVisitedOnce) {
    const Tin tin = Tin::random_points(Rect{{0, 0}, {3, 2}}, 200, 4, bumpy);
    for (const SampleAt at : {SampleAt::Corners, SampleAt::Centres}) {
        const MapGrid grid(tin.domain(), 61, 41, at);
        std::vector<int> visits(grid.size(), 0);
        for_each_sample(tin, grid, [&](std::size_t i, const auto&, const auto& w) {
            ++visits[i];
            EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
        });
        EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<long>(grid.size()));
    }
}

TEST(MapBake, HeightsMatchABruteForceSearch) {
    const Tin tin = Tin::random_points(Rect{{0, 0}, {3, 2}}, 300, 8, bumpy);
    for (const SampleAt at : {SampleAt::Corners, SampleAt::Centres}) {
        const MapGrid grid(tin.domain(), 37, 23, at);
        const MapImage map = bake_height_map(tin, grid);
        ASSERT_EQ(map.channels, 1);
        for (std::uint32_t row = 0; row < grid.height; ++row) {
            for (std::uint32_t col = 0; col < grid.width; ++col) {
                EXPECT_NEAR(map.at(col, row),
                            test::brute_force_height(tin, grid.position(col, row)), 1e-12);
            }
        }
    }
}

TEST(MapBake, NormalsOfAPlaneAreThePlanesNormal) {
    const test::Plane plane{0.3, -0.7, 2.0};
    const Tin tin = Tin::random_points(Rect{{0, 0}, {4, 4}}, 150, 2, plane);
    const double len = std::sqrt(0.3 * 0.3 + 0.7 * 0.7 + 1.0);
    const Vec3 expected{-0.3 / len, 0.7 / len, 1.0 / len};
    for (const NormalMode mode : {NormalMode::Smooth, NormalMode::Faceted}) {
        const MapImage map =
            bake_normal_map(tin, MapGrid(tin.domain(), 32, 32, SampleAt::Centres), mode);
        ASSERT_EQ(map.channels, 3);
        for (std::uint32_t row = 0; row < 32; ++row) {
            for (std::uint32_t col = 0; col < 32; ++col) {
                EXPECT_NEAR(map.at(col, row, 0), expected.x, 1e-9);
                EXPECT_NEAR(map.at(col, row, 1), expected.y, 1e-9);
                EXPECT_NEAR(map.at(col, row, 2), expected.z, 1e-9);
            }
        }
    }
    // Exaggerating heights tilts the normal further.
    const MapImage steep = bake_normal_map(tin, MapGrid(tin.domain(), 4, 4, SampleAt::Centres),
                                           NormalMode::Faceted, 2.0);
    const double len2 = std::sqrt(0.6 * 0.6 + 1.4 * 1.4 + 1.0);
    EXPECT_NEAR(steep.at(1, 1, 0), -0.6 / len2, 1e-9);
}

TEST(MapBake, FacetedNormalsAreTheContainingTrianglesNormals) {
    const Tin tin = Tin::random_points(Rect{{0, 0}, {3, 2}}, 80, 11, bumpy);
    const MapGrid grid(tin.domain(), 29, 19, SampleAt::Centres);
    const MapImage map = bake_normal_map(tin, grid, NormalMode::Faceted);
    for (std::uint32_t row = 0; row < grid.height; ++row) {
        for (std::uint32_t col = 0; col < grid.width; ++col) {
            const auto tris = test::triangles_containing(tin, grid.position(col, row));
            ASSERT_FALSE(tris.empty());
            const auto& t = tris.front();
            auto p = [&](VertexId v) {
                return Vec3{tin.position(v).x, tin.position(v).y, tin.height(v)};
            };
            // Independent normal: the cross product of two edges, normalised by hand.
            const Vec3 a = p(t[0]);
            const Vec3 u = p(t[1]) - a;
            const Vec3 w = p(t[2]) - a;
            const Vec3 n{u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
            const double l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
            if (tris.size() > 1) continue;  // on an edge either side is right
            EXPECT_NEAR(map.at(col, row, 0), n.x / l, 1e-9);
            EXPECT_NEAR(map.at(col, row, 1), n.y / l, 1e-9);
            EXPECT_NEAR(map.at(col, row, 2), n.z / l, 1e-9);
        }
    }
}

TEST(MapBake, SmoothNormalsAreUnitAndInterpolateVertexNormals) {
    const Tin tin = Tin::random_points(Rect{{0, 0}, {3, 2}}, 120, 6, bumpy);
    const std::vector<Vec3> vn = vertex_normals(tin);
    // At a vertex the map equals that vertex's normal: sample exactly at a vertex position by
    // a grid whose corner sits on the domain corner (a vertex).
    const MapImage corner = bake_normal_map(tin, MapGrid(tin.domain(), 2, 2, SampleAt::Corners));
    VertexId south_west;
    for (VertexId v : test::live_ids(tin)) {
        if (tin.position(v) == tin.domain().min) south_west = v;
    }
    ASSERT_TRUE(south_west.valid());
    EXPECT_NEAR(corner.at(0, 1, 0), vn[south_west.index()].x, 1e-12);
    EXPECT_NEAR(corner.at(0, 1, 2), vn[south_west.index()].z, 1e-12);
    const MapImage map = bake_normal_map(tin, MapGrid(tin.domain(), 40, 30, SampleAt::Centres));
    for (std::size_t i = 0; i < map.values.size(); i += 3) {
        EXPECT_NEAR(std::hypot(map.values[i], map.values[i + 1], map.values[i + 2]), 1.0, 1e-12);
        EXPECT_GT(map.values[i + 2], 0.0);
    }
}

TEST(MapBake, AlbedoFollowsMaterialAndMoisture) {
    Tin tin = Tin::flat_rectangle(Rect{{0, 0}, {2, 2}}, 0.0);
    const MaterialColours palette{{{1.0, 0.5, 0.25}, {0.1, 0.2, 0.3}}, 0.5};
    MapImage map = bake_albedo_map(tin, MapGrid(tin.domain(), 4, 4, SampleAt::Centres), palette);
    EXPECT_NEAR(map.at(1, 1, 0), 1.0, 1e-12);
    EXPECT_NEAR(map.at(1, 1, 2), 0.25, 1e-12);
    for (VertexId v : test::live_ids(tin)) {
        tin.set_material(v, 7);  // past the palette's end: the last colour
        tin.set_moisture(v, 1.0f);
    }
    map = bake_albedo_map(tin, MapGrid(tin.domain(), 4, 4, SampleAt::Centres), palette);
    EXPECT_NEAR(map.at(2, 3, 0), 0.05, 1e-12);  // 0.1 at half reflectance when soaked
    EXPECT_NEAR(map.at(2, 3, 2), 0.15, 1e-12);
    EXPECT_THROW(bake_albedo_map(tin, MapGrid(tin.domain(), 4, 4, SampleAt::Centres), {}),
                 std::invalid_argument);
}

}  // namespace
}  // namespace sandtin
