// Curvature-driven weathering (physics/curvature_weathering): crests wear and hollows fill
// with the volume kept, a plane is left alone, the bedrock is never cut, and a square block
// rounds from its corners first (seed 001 expects a cube to weather towards a sphere: the
// sharper the bend, the faster it wears).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "physics/curvature_weathering.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {
namespace {

/// A ridge along y at x = 1 on a 2 m x 1 m terrain: 0.1 m high, 0.2 m to each foot.
Tin ridge(std::size_t points = 6000) {
    return Tin::random_points(Rect::from_size(2, 1), points, 11, [](Vec2 p) {
        return std::max(0.0, 0.1 - 0.5 * std::abs(p.x - 1.0));
    });
}

TEST(CurvatureWeathering, ARidgeWearsAtItsCrestAndFillsItsFeetKeepingTheVolume) {
    Tin tin = ridge();
    const double volume0 = tin.volume();
    const std::vector<double> h0 = tin.vertices().height;
    double crest = test::highest_height(tin);
    double moved = 0.0;
    for (int it = 0; it < 30; ++it) {
        const WeatheringReport r = weather_terrain(tin, 1, {});
        ASSERT_GT(r.vertices_worn, 0u) << it;
        moved += r.volume_moved;
        const double now = test::highest_height(tin);
        EXPECT_LT(now, crest) << "the crest wears every iteration (" << it << ")";
        crest = now;
    }
    // Volume: each share leaves one vertex and enters another.
    EXPECT_NEAR(tin.volume(), volume0, 1e-12 * volume0);
    EXPECT_GT(moved, 1e-6);
    const VertexArrays& va = tin.vertices();
    int feet_raised = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        // The feet (a concave bend at 0.2 m) are where the sand gathers.
        const double from_crest = std::abs(va.position[v].x - 1.0);
        if (std::abs(from_crest - 0.2) < 0.01 && va.height[v] > h0[v]) ++feet_raised;
    }
    EXPECT_GT(feet_raised, 10);
}

TEST(CurvatureWeathering, SandTravelsAtMostOneEdgePerIteration) {
    // Only bent vertices wear, and they pass sand to their neighbours: after k iterations
    // nothing farther than k longest edges from the ridge's bends has moved.
    Tin tin = ridge();
    const std::vector<double> h0 = tin.vertices().height;
    const VertexArrays& va = tin.vertices();
    // Rings from the ridge: 0 on it (|x - 1| <= 0.2), then by hops along edges.
    std::vector<int> ring_of(va.size(), -1);
    std::vector<VertexId> front, next, around;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v] && std::abs(va.position[v].x - 1.0) <= 0.2) {
            ring_of[v] = 0;
            front.push_back(VertexId{v});
        }
    }
    for (int r = 1; !front.empty(); ++r, front.swap(next)) {
        next.clear();
        for (VertexId v : front) {
            tin.neighbours(v, around);
            for (VertexId w : around) {
                if (ring_of[w.value] >= 0) continue;
                ring_of[w.value] = r;
                next.push_back(w);
            }
        }
    }
    // A vertex one ring off the ridge has a bent star; each iteration then reaches one more.
    const int iterations = 8;
    weather_terrain(tin, iterations, {});
    int inside_changed = 0, outside = 0;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        if (ring_of[v] > iterations + 1) {
            ++outside;
            EXPECT_EQ(va.height[v], h0[v]) << "ring " << ring_of[v];
        } else if (va.height[v] != h0[v]) {
            ++inside_changed;
        }
    }
    EXPECT_GT(outside, 1000);
    EXPECT_GT(inside_changed, 100);
}

TEST(CurvatureWeathering, APlaneIsLeftBitForBit) {
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 3000, 12,
                                 [](Vec2 p) { return 0.2 + 0.3 * p.x - 0.1 * p.y; });
    const std::vector<double> h0 = tin.vertices().height;
    const WeatheringReport r = weather_terrain(tin, 5, {});
    EXPECT_EQ(r.vertices_worn, 0u);
    EXPECT_EQ(tin.vertices().height, h0);
}

TEST(CurvatureWeathering, NeverCutsTheBedrock) {
    // 2 mm of sand over a rock ridge: the crest has sand to lose only down to the rock.
    Tin tin = ridge(4000);
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) tin.set_bedrock(VertexId{v}, va.height[v] - 0.002);
    }
    const double volume0 = tin.volume();
    weather_terrain(tin, 40, {});
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        EXPECT_GE(va.height[v], va.bedrock[v]) << v;
    }
    EXPECT_NEAR(tin.volume(), volume0, 1e-12 * volume0);
}

TEST(CurvatureWeathering, ASquareBlockRoundsFromItsCornersFirst) {
    // A 0.5 m square block 0.1 m high with 5 cm walls. Its top corners bend two ways, the
    // middles of its top edges one way, its top's centre not at all: they wear in that order.
    auto block = [](Vec2 p) {
        const double out = std::max(std::abs(p.x), std::abs(p.y)) - 0.25;
        return 0.1 * std::clamp(1.0 - out / 0.05, 0.0, 1.0);
    };
    Tin tin = Tin::random_points(Rect{{-0.5, -0.5}, {0.5, 0.5}}, 20000, 13, block);
    weather_terrain(tin, 25, {});
    auto drop = [&](Vec2 p) { return 0.1 - tin.height_at(p).value(); };
    const double corner = drop({0.24, 0.24});
    const double edge = drop({0.24, 0.0});
    const double centre = drop({0.0, 0.0});
    EXPECT_GT(corner, 1.2 * edge);
    EXPECT_GT(edge, 1e-4);
    EXPECT_NEAR(centre, 0.0, 1e-15);  // the flat top does not bend: interpolation's rounding
}

TEST(CurvatureWeathering, AHigherPowerSparesGentleBends) {
    // Two bends on one ridge profile: a sharp crest and a gentle shoulder. With power 1 the
    // shoulder wears; with power 4 it wears far less relative to the crest.
    auto profile = [](Vec2 p) {
        const double x = std::abs(p.x - 1.0);
        return x < 0.05 ? 0.1 - 0.6 * x : std::max(0.0, 0.07 - 0.15 * (x - 0.05));
    };
    double ratio[2];
    const double power[2] = {1.0, 4.0};
    for (int k = 0; k < 2; ++k) {
        Tin tin = Tin::random_points(Rect::from_size(2, 1), 8000, 14, profile);
        const std::vector<double> h0 = tin.vertices().height;
        WeatheringSettings s;
        s.power = power[k];
        weather_terrain(tin, 3, s);
        const VertexArrays& va = tin.vertices();
        double crest = 0.0, gentle = 0.0;
        for (std::size_t v = 0; v < va.size(); ++v) {
            const double x = std::abs(va.position[v].x - 1.0);
            const double lost = std::max(0.0, h0[v] - va.height[v]);
            if (x < 0.02) crest = std::max(crest, lost);
            if (x > 0.3 && x < 0.5) gentle = std::max(gentle, lost);
        }
        ASSERT_GT(crest, 0.0);
        ratio[k] = gentle / crest;
    }
    EXPECT_LT(ratio[1], 0.5 * ratio[0]);
}

TEST(CurvatureWeathering, RefusesSettingsOutOfRange) {
    Tin tin = ridge(500);
    WeatheringSettings s;
    s.strength = 1.5;
    EXPECT_THROW(weather_terrain(tin, 1, s), std::invalid_argument);
    s = {};
    s.power = 0.5;
    EXPECT_THROW(weather_terrain(tin, 1, s), std::invalid_argument);
    s = {};
    EXPECT_THROW(weather_terrain(tin, -1, s), std::invalid_argument);
    const std::vector<VertexId> one{VertexId{0}};
    const std::vector<double> bad{2.0};
    EXPECT_THROW(weather_vertices(tin, one, bad, s), std::invalid_argument);
    const std::vector<double> two{1.0, 1.0};
    EXPECT_THROW(weather_vertices(tin, one, two, s), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin
