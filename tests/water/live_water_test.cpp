// Water that runs beside an edited terrain (water/live_water.hpp): a dry terrain costs nothing;
// a nozzle adds what its rate says and the terrain holds it (volume = rate x time, walls all
// round); an edit that re-triangulates rebuilds the pipes and a raised vertex sheds its water;
// depths set from outside (an undo) are taken over and not overwritten; water that comes to
// rest stops stepping until the terrain under or beside it changes, or a side opens (edits
// elsewhere cost it nothing); a shower rains on its disc alone; Clear takes all of it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"
#include "tools/simplifier.hpp"
#include "water/live_water.hpp"

namespace sandtin {
namespace {
namespace live_water_test {

Tin bowl() {
    return Tin::random_points(Rect::from_size(1.0, 1.0), 1200, 4, [](Vec2 p) {
        return 0.2 * ((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5));
    });
}

/// `frames` frames of 1/60 s each, with `nozzle` held (0 L/s: none).
LiveWaterFrame frames(LiveWater& water, int count, double litres_per_second = 0.0,
                      const LiveWaterSettings& settings = {}) {
    LiveWaterFrame total;
    for (int i = 0; i < count; ++i) {
        if (litres_per_second > 0.0) water.add_nozzle({{0.5, 0.5}, litres_per_second});
        const LiveWaterFrame f = water.advance(1.0 / 60.0, settings, 1e9);
        total.ran = total.ran || f.ran;
        total.rebuilt = total.rebuilt || f.rebuilt;
        total.seconds += f.seconds;
        total.steps += f.steps;
        total.added += f.added;
        total.written += f.written;
    }
    return total;
}

TEST(LiveWater, ADryTerrainCostsNothing) {
    Tin tin = bowl();
    LiveWater water(tin);
    const LiveWaterFrame f = frames(water, 30);
    EXPECT_FALSE(f.ran);
    EXPECT_FALSE(f.rebuilt);
    EXPECT_EQ(f.steps, 0u);
    EXPECT_TRUE(water.idle({}));
    // Nor does sculpting a dry terrain wake it.
    tin.set_height(VertexId{100}, 0.3);
    EXPECT_FALSE(frames(water, 5).ran);
}

TEST(LiveWater, ANozzleAddsWhatItsRateSaysAndTheTerrainHoldsIt) {
    Tin tin = bowl();
    LiveWater water(tin);
    const LiveWaterFrame f = frames(water, 60, 0.1);  // 0.1 L/s for one second
    EXPECT_TRUE(f.ran);
    EXPECT_NEAR(f.seconds, 1.0, 1e-12);
    EXPECT_NEAR(f.added, 1e-4, 1e-16);
    EXPECT_NEAR(test::water_volume(tin), 1e-4, 1e-16);
    EXPECT_NEAR(water.measure().volume, 1e-4, 1e-16);
    EXPECT_GT(water.measure().wet_vertices, 1u);  // it spread from the nozzle's vertex
    // With no source, walls all round: the volume stays while the water flows.
    frames(water, 60);
    EXPECT_NEAR(test::water_volume(tin), 1e-4, 1e-16);
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(LiveWater, EditsUnderTheWaterAreFollowed) {
    Tin tin = bowl();
    LiveWater water(tin);
    frames(water, 120, 0.2);
    // A vertex raised far above the pond sheds its water.
    VertexId wettest;
    double deepest = 0.0;
    for (std::uint32_t v = 0; v < tin.vertices().size(); ++v) {
        if (tin.is_alive(VertexId{v}) && !tin.is_boundary(VertexId{v}) &&
            tin.vertices().water_depth[v] > deepest) {
            deepest = tin.vertices().water_depth[v];
            wettest = VertexId{v};
        }
    }
    ASSERT_GT(deepest, 0.0);
    tin.set_height(wettest, tin.height(wettest) + 0.2);
    frames(water, 60);
    EXPECT_LT(tin.vertices().water_depth[wettest.index()], 0.5 * deepest);
    // A new vertex re-triangulates: the pipes are rebuilt from the terrain, and the new vertex
    // (in the pond) holds water.
    const VertexId added = tin.insert_point_on_surface({0.503, 0.497});
    const LiveWaterFrame f = frames(water, 1);
    EXPECT_TRUE(f.rebuilt);
    EXPECT_GT(tin.vertices().water_depth[added.index()], 0.0);
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(LiveWater, DepthsSetFromOutsideAreTakenOver) {
    Tin tin = bowl();
    LiveWater water(tin);
    frames(water, 60, 0.1);
    // An undo takes the water away: it must not come back from the pipes.
    for (std::uint32_t v = 0; v < tin.vertices().size(); ++v)
        if (tin.is_alive(VertexId{v})) tin.set_water_depth(VertexId{v}, 0.0);
    frames(water, 30);
    EXPECT_EQ(test::water_volume(tin), 0.0);
    EXPECT_EQ(water.measure().wet_vertices, 0u);
    // And a redo puts some back, which then flows.
    tin.set_water_depth(VertexId{200}, 0.01);
    const double put = tin.vertices().lumped_area[200] * 0.01;
    const LiveWaterFrame f = frames(water, 30);
    EXPECT_TRUE(f.ran);
    EXPECT_NEAR(test::water_volume(tin), put, 1e-12 * put);
}

TEST(LiveWater, WaterAtRestStopsSteppingUntilTheTerrainChanges) {
    Tin tin = bowl();
    LiveWater water(tin);
    frames(water, 30, 0.2);
    LiveWaterSettings still;
    still.friction = 4.0;  // a lake that stills within a minute
    int waited = 0;
    while (!water.resting() && waited < 60 * 600) {
        frames(water, 60, 0.0, still);
        waited += 60;
    }
    ASSERT_TRUE(water.resting()) << "after " << waited / 60 << " s";
    EXPECT_TRUE(water.idle(still));
    const LiveWaterFrame quiet = frames(water, 10, 0.0, still);
    EXPECT_FALSE(quiet.ran);
    EXPECT_EQ(quiet.steps, 0u);
    // Its surface is level where it is deep (the bowl's pond).
    double low = 1e9, high = -1e9;
    const VertexArrays& va = tin.vertices();
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || va.water_depth[v] < 1e-3) continue;
        low = std::min(low, va.height[v] + va.water_depth[v]);
        high = std::max(high, va.height[v] + va.water_depth[v]);
    }
    ASSERT_LT(low, high + 1.0);
    EXPECT_LT(high - low, 1e-4);
    // Edits away from the pond (the erosion sliding on a far slope) leave it at rest: they
    // cost no step, so they stay local. A vertex far from the pond here: the bowl's corner.
    VertexId far, wet;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        if (!far.valid() || length(va.position[v] - Vec2{0.5, 0.5}) >
                                length(va.position[far.index()] - Vec2{0.5, 0.5}))
            far = VertexId{v};
        if (!wet.valid() || va.water_depth[v] > va.water_depth[wet.index()]) wet = VertexId{v};
    }
    ASSERT_EQ(va.water_depth[far.index()], 0.0);
    for (int i = 0; i < 5; ++i) {
        tin.set_height(far, tin.height(far) - 0.001);
        EXPECT_FALSE(frames(water, 1, 0.0, still).ran) << "an edit far from the water woke it";
    }
    // An edit under the pond wakes it: the next frame sees the edit and steps.
    tin.set_height(wet, tin.height(wet) - 0.01);
    EXPECT_TRUE(frames(water, 1, 0.0, still).ran);
}

TEST(LiveWater, OpeningASideWakesWaterAtRest) {
    // A plane tilted to the west with walls all round: the water rests against the west wall
    // until that side opens.
    Tin tin =
        Tin::random_points(Rect::from_size(1.0, 1.0), 800, 5, [](Vec2 p) { return 0.05 * p.x; });
    LiveWater water(tin);
    for (std::uint32_t v = 0; v < tin.vertices().size(); ++v)
        if (tin.is_alive(VertexId{v}) && tin.position(VertexId{v}).x < 0.2)
            tin.set_water_depth(VertexId{v}, 0.02 - 0.05 * tin.position(VertexId{v}).x);
    LiveWaterSettings walls;
    walls.friction = 4.0;
    for (int s = 0; s < 600 && !water.resting(); ++s)
        frames(water, 60, 0.0, walls);
    ASSERT_TRUE(water.resting());
    const double held = test::water_volume(tin);
    LiveWaterSettings open = walls;
    open.open.west = true;
    const LiveWaterFrame f = frames(water, 60, 0.0, open);
    EXPECT_TRUE(f.ran);
    EXPECT_LT(test::water_volume(tin), held);
}

TEST(LiveWater, ClearTakesAllTheWaterAndSaysHowMuch) {
    Tin tin = bowl();
    LiveWater water(tin);
    frames(water, 60, 0.1);
    EXPECT_NEAR(water.clear(), 1e-4, 1e-16);
    EXPECT_EQ(test::water_volume(tin), 0.0);
    EXPECT_FALSE(frames(water, 10).ran);
}

TEST(LiveWater, AShowerRainsItsRateOnItsDiscAlone) {
    // The Rain tool's shower, 3 600 mm/h (1 mm/s) on a disc of 15 cm, held 30 frames with the
    // water standing still: every vertex in the disc takes 0.5 mm, none outside any, and the
    // volume is 0.5 mm over the disc's vertices' lumped areas (water_sources.hpp: rain falls on
    // the vertices within the disc).
    Tin tin = bowl();
    LiveWater water(tin);
    LiveWaterSettings still;
    still.flowing = false;
    const Vec2 centre{0.4, 0.6};
    const double radius = 0.15;
    for (int i = 0; i < 30; ++i) {
        water.add_shower({3600.0, centre, radius});
        water.advance(1.0 / 60.0, still, 1e9);
    }
    const VertexArrays& va = tin.vertices();
    double area_inside = 0.0;
    std::size_t inside = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const double r = length(va.position[v] - centre);
        if (r < radius - 1e-9) {
            EXPECT_NEAR(va.water_depth[v], 0.5e-3, 1e-12) << "vertex " << v;
            area_inside += va.lumped_area[v];
            ++inside;
        } else if (r > radius + 1e-9) {
            EXPECT_EQ(va.water_depth[v], 0.0) << "vertex " << v << " outside the disc";
        }
    }
    EXPECT_GT(inside, 50u);
    EXPECT_NEAR(test::water_volume(tin), 0.5e-3 * area_inside, 1e-12);
    // Released: no more rain, and the still water stays as it is.
    const double held = test::water_volume(tin);
    water.advance(1.0 / 60.0, still, 1e9);
    EXPECT_EQ(test::water_volume(tin), held);
    EXPECT_THROW(water.add_shower({-1.0, centre, radius}), std::invalid_argument);
    EXPECT_THROW(water.add_shower({100.0, centre, 0.0}), std::invalid_argument);
    EXPECT_THROW(water.add_shower({100.0, {std::nan(""), 0.5}, radius}), std::invalid_argument);
}

TEST(LiveWater, SpeedsShowWhereTheWaterRunsAndFallAsItRests) {
    Tin tin = bowl();
    LiveWater water(tin);
    frames(water, 60, 0.05);  // 0.05 L/s at the bowl's centre for a second
    const VertexArrays& va = tin.vertices();
    ASSERT_EQ(water.speeds().size(), va.size());
    float running = 0.0f;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        if (va.water_depth[v] == 0.0) {
            EXPECT_EQ(water.speeds()[v], 0.0f) << "dry vertex " << v;
        }
        EXPECT_TRUE(std::isfinite(water.speeds()[v]) && water.speeds()[v] >= 0.0f);
        running = std::max(running, water.speeds()[v]);
    }
    EXPECT_GT(running, 1e-3f) << "water poured into a bowl runs";
    // Left alone the pond comes to rest; its speeds fall with its fluxes.
    for (int i = 0; i < 600 && !water.resting(); ++i)
        water.advance(1.0, {}, 1e9);
    ASSERT_TRUE(water.resting());
    const float still = *std::max_element(water.speeds().begin(), water.speeds().end());
    EXPECT_LT(still, 1e-2f * running);
    // Standing water (Flow off) shows no speed at all, even under a nozzle.
    LiveWaterSettings standing;
    standing.flowing = false;
    water.add_nozzle({{0.5, 0.5}, 0.05});
    water.advance(1.0 / 60.0, standing, 1e9);
    EXPECT_EQ(*std::max_element(water.speeds().begin(), water.speeds().end()), 0.0f);
}

TEST(LiveWater, ErodingWaterCarvesTheSlopeDropsAFanAndKeepsTheSand) {
    // A stream poured near the top of a sand slope with Erode on: the sand it picks up and
    // drops moves the terrain's heights, and the terrain's volume plus the sand in the water
    // stays what it was, frame after frame (sediment_transport.hpp's conservation, through
    // the write-back into the terrain).
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 1200, 9,
                                 [](Vec2 p) { return 0.3 * (1.0 - p.x); });
    const std::vector<double> start(tin.vertices().height);
    const double sand = tin.volume();
    LiveWater water(tin);
    LiveWaterSettings eroding;
    eroding.erode = true;
    eroding.friction = 4.0;  // the pond stills within seconds
    std::size_t eroded = 0;
    for (int i = 0; i < 60; ++i) {
        water.add_nozzle({{0.15, 0.5}, 0.05});
        eroded += water.advance(1.0 / 60.0, eroding, 1e9).eroded;
        ASSERT_NEAR(tin.volume() + water.suspended(), sand, 1e-12 * sand) << "frame " << i;
    }
    EXPECT_GT(eroded, 0u);
    EXPECT_GT(water.suspended(), 0.0) << "running water carries sand";
    ASSERT_FALSE(water.sediment().empty());
    EXPECT_GT(*std::max_element(water.sediment().begin(), water.sediment().end()), 0.0f);
    const VertexArrays& va = tin.vertices();
    const auto deepest_change = [&](double sign) {
        double most = 0.0;
        for (std::uint32_t v = 0; v < va.size(); ++v)
            most = std::max(most, sign * (va.height[v] - start[v]));
        return most;
    };
    EXPECT_GT(deepest_change(-1.0), 1e-4) << "the stream cut no channel";
    // Left alone, the water comes to rest and what it carried lies on the terrain.
    for (int i = 0; i < 600 && !water.resting(); ++i)
        water.advance(1.0, eroding, 1e9);
    ASSERT_TRUE(water.resting());
    EXPECT_EQ(water.suspended(), 0.0);
    EXPECT_NEAR(tin.volume(), sand, 1e-12 * sand);
    EXPECT_GT(deepest_change(1.0), 1e-4) << "the stream dropped no sand";
}

TEST(LiveWater, WithoutErodeTheSandStaysPut) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 9,
                                 [](Vec2 p) { return 0.3 * (1.0 - p.x); });
    const std::vector<double> start(tin.vertices().height);
    LiveWater water(tin);
    for (int i = 0; i < 60; ++i) {
        water.add_nozzle({{0.15, 0.5}, 0.05});
        EXPECT_EQ(water.advance(1.0 / 60.0, {}, 1e9).eroded, 0u);
    }
    EXPECT_EQ(tin.vertices().height, start);
    EXPECT_TRUE(water.sediment().empty());
    EXPECT_EQ(water.suspended(), 0.0);
}

TEST(LiveWater, DetailSplitsTheLongWetEdgesAndKeepsTheWaterAndTheSand) {
    // A coarse terrain (12.5 cm triangles, as an elevation model's flats are to its water)
    // with a pond in a hollow: with a detail of 4 cm the edges under the water are split over
    // a few frames until none with water at both ends is longer; the water and the sand
    // keep their volumes through every split; the dry slopes keep their triangles.
    Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 8, 8, [](Vec2 p) {
        return 0.2 * ((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5));
    });
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.height[v] < 0.004) tin.set_water_depth(VertexId{v}, 0.006 - va.height[v]);
    const double water0 = test::water_volume(tin), sand0 = tin.volume();
    const std::size_t vertices0 = tin.vertex_count();
    LiveWater water(tin);
    LiveWaterSettings detailed;
    detailed.detail = 0.04;
    std::size_t refined = 0;
    for (int i = 0; i < 20; ++i) {
        refined += water.advance(1.0 / 60.0, detailed, 1e9).refined;
        ASSERT_NEAR(test::water_volume(tin), water0, 1e-12 * water0) << "frame " << i;
        ASSERT_NEAR(tin.volume(), sand0, 1e-12 * sand0) << "frame " << i;
    }
    EXPECT_GT(refined, 10u);
    EXPECT_EQ(tin.vertex_count(), vertices0 + refined);
    EXPECT_TRUE(tin.check_valid().ok());
    std::size_t long_wet = 0;
    for (const auto& t : tin.triangles()) {
        for (int k = 0; k < 3; ++k) {
            const VertexId a = t[k], b = t[(k + 1) % 3];
            if (va.water_depth[a.index()] >= kFilmDepth &&
                va.water_depth[b.index()] >= kFilmDepth &&
                length(va.position[a.index()] - va.position[b.index()]) > 0.04)
                ++long_wet;
        }
    }
    EXPECT_EQ(long_wet, 0u) << "wet edges longer than the detail are left";
    // Without detail nothing is split.
    Tin plain = Tin::regular_grid(Rect::from_size(1.0, 1.0), 8, 8);
    plain.set_water_depth(VertexId{40}, 0.01);
    LiveWater still(plain);
    const std::size_t before = plain.vertex_count();
    for (int i = 0; i < 5; ++i)
        EXPECT_EQ(still.advance(1.0 / 60.0, {}, 1e9).refined, 0u);
    EXPECT_EQ(plain.vertex_count(), before);
}

TEST(LiveWater, DetailGoesOnceTheGroundIsDryAgain) {
    // Flat ground under a sheet of water, refined by the detail; the water evaporates; the
    // vertices it left are handed to the simplifier (take_dried), which now takes the
    // interior ones it refused while they were wet. Border vertices stay, as they always do.
    Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 8, 8);
    const std::size_t vertices0 = tin.vertex_count();
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v)
        tin.set_water_depth(VertexId{v}, 0.002);
    LiveWater water(tin);
    LiveWaterSettings detailed;
    detailed.detail = 0.06;
    for (int i = 0; i < 10; ++i)
        water.advance(1.0 / 60.0, detailed, 1e9);
    const std::size_t refined = tin.vertex_count() - vertices0;
    ASSERT_GT(refined, 50u);
    // While wet, the simplifier leaves the refined ground alone.
    Simplifier simplifier;
    for (const VertexId v : test::live_ids(tin))
        simplifier.enqueue(v);
    EXPECT_EQ(simplifier.run(tin, {}).removed, 0u);
    // A hot wind dries it within seconds.
    LiveWaterSettings drying = detailed;
    drying.evaporation_mm_per_hour = 20000.0;
    for (int i = 0; i < 120 && test::water_volume(tin) > 0.0; ++i)
        water.advance(0.1, drying, 1e9);
    ASSERT_EQ(test::water_volume(tin), 0.0);
    const std::vector<VertexId> dried = water.take_dried();
    EXPECT_GE(dried.size(), tin.vertex_count()) << "every vertex held water and dried";
    EXPECT_TRUE(water.take_dried().empty());
    simplifier.enqueue(dried);
    const SimplifyReport r = simplifier.run(tin, {});
    EXPECT_GT(r.removed, 0u);
    std::size_t interior_left = 0;
    for (const VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        const bool border = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
        interior_left += border ? 0 : 1;
    }
    EXPECT_EQ(interior_left, 0u) << "flat dry ground keeps interior vertices";
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(LiveWater, BadArgumentsAreRefused) {
    Tin tin = bowl();
    LiveWater water(tin);
    EXPECT_THROW(water.advance(-1.0, {}, 10.0), std::invalid_argument);
    EXPECT_THROW(water.advance(std::nan(""), {}, 10.0), std::invalid_argument);
    LiveWaterSettings bad;
    bad.rain_mm_per_hour = -5.0;
    EXPECT_THROW(water.advance(0.1, bad, 10.0), std::invalid_argument);
}

}  // namespace live_water_test
}  // namespace
}  // namespace sandtin
