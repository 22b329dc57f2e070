// Sources and borders of the water (water/water_sources.hpp, water/water_borders.hpp): rain and
// nozzles add exactly what their rates say (area x rate x time, litres per second x time),
// evaporation takes at most what is there, an open side drains a tilted plane and counts what
// left, and walls hold it. The balance volume = before + added - evaporated - left is exact.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tin/tin.hpp"
#include "water/tin_water_mesh.hpp"
#include "water/virtual_pipes.hpp"
#include "water/water_borders.hpp"
#include "water/water_sources.hpp"

namespace sandtin {
namespace {
namespace water_sources_test {

Tin gentle_bowl() {
    return Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 30, 30,
        [](Vec2 p) { return 0.1 * ((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5)); },
        TinOptions{false});
}

/// Steps the water and its sources for `seconds`; returns the sources' totals.
SourceReport run(VirtualPipes& w, const WaterSources& s, double seconds) {
    SourceReport total;
    double t = 0.0;
    while (t < seconds) {
        const double dt = std::min({w.stable_time_step(), 0.05, seconds - t});
        const SourceReport r = apply_sources(w, s, dt);
        total.added += r.added;
        total.evaporated += r.evaporated;
        w.step(dt);
        t += dt;
    }
    return total;
}

TEST(WaterSources, RainAndANozzleAddWhatTheirRatesSay) {
    const Tin tin = gentle_bowl();
    VirtualPipes w(water_mesh_of(tin));
    WaterSources s;
    s.rain.push_back({36.0, {}, 0.0});       // 36 mm/h on the whole 1 m²: 1e-5 m³/s
    s.nozzles.push_back({{0.3, 0.6}, 0.5});  // 0.5 L/s
    const SourceReport r = run(w, s, 20.0);
    const double expected = 20.0 * (36e-3 / 3600.0 * 1.0 + 0.5e-3);
    EXPECT_NEAR(r.added, expected, 1e-12 * expected);
    EXPECT_NEAR(w.volume(), expected, 1e-12 * expected);  // closed walls: nothing left
    EXPECT_EQ(w.volume_left(), 0.0);
    // Rain on a disc falls on its vertices only.
    VirtualPipes d(water_mesh_of(tin));
    WaterSources disc;
    disc.rain.push_back({100.0, {0.25, 0.25}, 0.1});
    apply_sources(d, disc, 1.0);
    for (std::size_t v = 0; v < d.vertex_count(); ++v) {
        const bool inside = length(d.mesh().position[v] - Vec2{0.25, 0.25}) <= 0.1;
        EXPECT_EQ(d.depth(v) > 0.0, inside) << v;
    }
}

TEST(WaterSources, AJetLandsOnTheVerticesWithinItsRadiusAtOneDepth) {
    // 0.2 L/s for 0.05 s through a jet of 8 cm over a 30 x 30 grid (3.3 cm spacing): every
    // vertex within 8 cm rises by the same depth, none outside, and the volume is the rate's.
    const Tin tin = gentle_bowl();
    VirtualPipes w(water_mesh_of(tin));
    WaterSources s;
    const Vec2 at{0.41, 0.57};
    s.nozzles.push_back({at, 0.2, 0.08});
    const SourceReport r = apply_sources(w, s, 0.05);
    EXPECT_NEAR(r.added, 1e-5, 1e-17);
    EXPECT_NEAR(w.volume(), 1e-5, 1e-17);
    double rise = 0.0;
    int under = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        const bool inside = length(w.mesh().position[v] - at) <= 0.08;
        EXPECT_EQ(w.depth(v) > 0.0, inside) << v;
        if (!inside) continue;
        if (under++ == 0) rise = w.depth(v);
        EXPECT_NEAR(w.depth(v), rise, 1e-15) << v;
    }
    EXPECT_GT(under, 15);
    // A jet narrower than the mesh (no vertex within 1 mm of a point between vertices) lands
    // on the vertex nearest to it, as a radius of 0 does.
    VirtualPipes narrow(water_mesh_of(tin)), point(water_mesh_of(tin));
    WaterSources thin, exact;
    thin.nozzles.push_back({{0.41, 0.57}, 0.2, 0.001});
    exact.nozzles.push_back({{0.41, 0.57}, 0.2});
    apply_sources(narrow, thin, 0.05);
    apply_sources(point, exact, 0.05);
    int wet = 0;
    for (std::size_t v = 0; v < w.vertex_count(); ++v) {
        EXPECT_EQ(narrow.depth(v), point.depth(v)) << v;
        wet += narrow.depth(v) > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(wet, 1);
}

TEST(WaterSources, EvaporationTakesAtMostWhatIsThereAndTheBalanceIsExact) {
    const Tin tin = gentle_bowl();
    VirtualPipes w(water_mesh_of(tin));
    w.add_water(w.vertex_count() / 2, 0.001);  // 1 L near the middle
    const double before = w.volume();
    WaterSources s;
    s.evaporation_mm_per_hour = 360.0;  // 0.1 mm/s: strong, to dry the shore within the run
    const SourceReport r = run(w, s, 30.0);
    EXPECT_GT(r.evaporated, 0.0);
    EXPECT_LT(r.evaporated, before);
    EXPECT_NEAR(w.volume(), before - r.evaporated, 1e-12 * before);
    for (double depth : w.depths())
        EXPECT_GE(depth, 0.0);
    // Everything evaporates, in time, and no more than was there.
    const SourceReport rest = run(w, s, 600.0);
    EXPECT_EQ(w.volume(), 0.0);
    EXPECT_NEAR(r.evaporated + rest.evaporated, before, 1e-12 * before);
}

TEST(WaterBorders, AnOpenSideDrainsATiltedPlaneAndWallsHoldIt) {
    // A plane falling towards x = 0 at 5 %, 1 cm of water on it.
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 30, 30, [](Vec2 p) { return 0.05 * p.x; }, TinOptions{false});
    const auto wet = [&] {
        VirtualPipes w(water_mesh_of(tin));
        for (std::size_t v = 0; v < w.vertex_count(); ++v)
            w.set_depth(v, 0.01);
        return w;
    };
    VirtualPipes open = wet();
    const double before = open.volume();
    OpenSides west;
    west.west = true;
    EXPECT_NEAR(open_borders(open, tin.domain(), west), 1.0, 1e-12);  // the whole west side
    run(open, {}, 60.0);
    EXPECT_NEAR(open.volume() + open.volume_left(), before, 1e-12 * before);
    EXPECT_LT(open.volume(), 0.05 * before) << "the plane drained through its low side";
    // The same plane walled all round keeps its water, gathered against the low wall.
    VirtualPipes walled = wet();
    run(walled, {}, 60.0);
    EXPECT_EQ(walled.volume_left(), 0.0);
    EXPECT_NEAR(walled.volume(), before, 1e-12 * before);
    // The high side open: the water runs away from it and stays.
    VirtualPipes high = wet();
    OpenSides east;
    east.east = true;
    open_borders(high, tin.domain(), east);
    run(high, {}, 60.0);
    EXPECT_GT(high.volume(), 0.9 * before);
}

TEST(WaterSources, BadRatesAreRefusedAndChangeNothing) {
    const Tin tin = gentle_bowl();
    VirtualPipes w(water_mesh_of(tin));
    WaterSources s;
    s.rain.push_back({-1.0, {}, 0.0});
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    s.rain = {{1.0, {}, std::nan("")}};
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    s.rain.clear();
    s.nozzles.push_back({{0.5, 0.5}, -0.1});
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    s.nozzles = {{{0.5, 0.5}, 0.1, -0.01}};  // a negative jet radius
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    s.nozzles = {{{0.5, 0.5}, 0.1, std::nan("")}};
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    s.nozzles.clear();
    s.evaporation_mm_per_hour = std::nan("");
    EXPECT_THROW(apply_sources(w, s, 1.0), std::invalid_argument);
    EXPECT_EQ(w.volume(), 0.0);
    EXPECT_THROW(w.set_outflow_width(0, -1.0), std::invalid_argument);
}

}  // namespace water_sources_test
}  // namespace
}  // namespace sandtin
