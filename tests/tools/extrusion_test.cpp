// Extrusion (material pushing): the volume a stamp displaces goes into a ridge outside O, ahead
// of and beside the motion, and a stamp or stroke with extrusion conserves volume within 1 % of
// what it displaced. Oracles: Tin::volume() and a brute-force per-triangle volume; the
// displaced volume measured on a twin terrain stamped without extrusion (or, for strokes, the
// cut integrated on a fine grid); the deposit located by sampling the surface before and after.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "geom/polygon.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/extrusion.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/stamp.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {
namespace {

using test::inside_polygon;
using test::live_ids;
using test::mesh_is_sound;

Tin terrain() {
    return test::smooth_terrain(test::kUnitSquare, 20000, 201, test::rolling_sand);
}

ToolSpec spec_of(const std::string& asset, bool extrude) {
    ToolSpec s = load_tool_asset(asset);
    s.extrude = extrude;
    return s;
}

/// Where the surface rose, integrated on a grid: total, in the rear sector (more than 135
/// degrees from the motion, seen from the tool centre) and in the front half.
struct Deposit {
    double total = 0.0;
    double rear = 0.0;
    double front = 0.0;
};

Deposit deposit_around(const std::vector<Vec2>& pts, const std::vector<double>& before,
                       const std::vector<double>& after, double cell_area, Vec2 centre,
                       Vec2 motion) {
    Deposit d;
    const Vec2 m = motion / length(motion);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const double rise = std::max(0.0, after[i] - before[i]) * cell_area;
        d.total += rise;
        const Vec2 r = pts[i] - centre;
        const double c = dot(r, m) / std::max(length(r), 1e-300);
        if (c < -std::sqrt(0.5)) d.rear += rise;
        if (c > 0.0) d.front += rise;
    }
    return d;
}

struct StampCase {
    std::string asset;
    double depth;  ///< m below the sand at the centre
    double angle;
};

TEST(Extrusion, StampConservesVolumeAndDepositsOutsideOAheadOfTheMotion) {
    const StampCase cases[] = {{"circle", 0.015, 0.4}, {"box", 0.012, 2.0}, {"ball", 0.02, -1.0}};
    for (const StampCase& c : cases) {
        SCOPED_TRACE(c.asset);
        const Tool with = Tool::build(spec_of(c.asset, true));
        const Tool without = Tool::build(spec_of(c.asset, false));
        Tin tin = terrain();
        Tin twin = terrain();
        SculptContext context(tin.domain()), twin_context(twin.domain());
        ToolPlacement at{{0.5, 0.5}, c.angle, 0.0};
        at.bottom = *tin.height_at(at.centre) - c.depth;
        const Vec2 motion{std::cos(c.angle), std::sin(c.angle)};

        // The displaced volume, measured on the twin without extrusion.
        const double v0 = twin.volume();
        ASSERT_TRUE(stamp(twin, without, at, twin_context, motion).applied);
        const double displaced = v0 - twin.volume();
        ASSERT_GT(displaced, 1e-7);

        const Tin before = Tin::from_snapshot(tin.snapshot());
        const Rect around{{0.3, 0.3}, {0.7, 0.7}};
        const std::vector<Vec2> grid = test::grid_points(around, 401, 401);
        const std::vector<double> h0 = test::surface_at(tin, grid);
        const StampReport r = stamp(tin, with, at, context, motion);
        ASSERT_TRUE(r.applied);
        EXPECT_TRUE(mesh_is_sound(tin));
        const double change = tin.volume() - v0;
        EXPECT_LE(std::abs(change), 0.01 * displaced)
            << "net change " << change << " m^3 for " << displaced << " m^3 displaced";
        EXPECT_NEAR(tin.volume(), test::brute_force_volume(tin), 1e-12);
        // The report agrees with the measurement (to the same 1 %).
        EXPECT_NEAR(r.displaced_volume, displaced, 0.01 * displaced);
        EXPECT_NEAR(r.deposited_volume, r.displaced_volume, 0.01 * displaced);

        // No vertex inside O rose above the pre-stamp sand (beyond the simplifier's
        // volume-conserving shifts).
        const std::vector<Vec2> outer = test::rotate_all(with.shape().outer, at.centre, at.angle);
        const double tol = context.settings.simplify.tolerance;
        LocateHint hint;
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            if (!inside_polygon(p, outer)) continue;
            EXPECT_LE(tin.height(v), *before.height_at(p, &hint) + tol) << p.x << ", " << p.y;
        }
        // The ridge: where the surface rose, measured on the grid.
        const std::vector<double> h1 = test::surface_at(tin, grid);
        const double cell = (around.width() / 400) * (around.height() / 400);
        const Deposit d = deposit_around(grid, h0, h1, cell, at.centre, motion);
        EXPECT_GT(d.total, 0.5 * displaced) << "the displaced sand should reappear as a ridge";
        EXPECT_LE(d.rear, 0.05 * d.total)
            << "deposit behind the tool: " << d.rear << " of " << d.total << " m^3";
        EXPECT_GT(d.front, d.total - d.front) << "more should go ahead than behind";
    }
}

TEST(Extrusion, RidgeHeightMatchesTheAnalyticRingOnSparseAndDenseTerrain) {
    // One stamp into flat sand, no motion: the ridge goes all around with the same weight
    // (the cut is the same everywhere), so its height is the parabolic ring's
    //   V = H * integral over s in [0, w] of (1 - (2s/w - 1)^2) * 2 pi (R_o + s) ds
    //     = H * 2 pi (2 w R_o / 3 + w^2 / 3).
    // The peak rise must be that H whatever the density of the terrain: raising only a few
    // inserted vertices on a dense terrain held the volume in needles several times higher.
    for (const int points : {400, 40000}) {
        SCOPED_TRACE(std::to_string(points) + " points");
        Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), static_cast<std::size_t>(points), 7,
                                     [](Vec2) { return 0.1; });
        SculptContext context(tin.domain());
        ToolSpec spec;
        spec.contour = ContourKind::Circle;
        spec.radius = 0.04;
        spec.control_points = 48;
        spec.extrude = true;
        const Tool tool = Tool::build(spec);
        const Vec2 centre{0.5, 0.5};
        const StampReport r = stamp(tin, tool, {centre, 0.0, 0.1 - 0.012}, context);
        ASSERT_TRUE(r.applied);
        EXPECT_NEAR(r.deposited_volume, r.displaced_volume, 0.01 * r.displaced_volume);
        const double w = tool.extrusion_width();
        const double r_outer = spec.radius + tool.shape().gap;
        const double expected =
            r.displaced_volume / (2.0 * std::numbers::pi * (2.0 * w * r_outer / 3.0 + w * w / 3.0));
        double peak = 0.0;
        const VertexArrays& va = tin.vertices();
        for (std::uint32_t i = 0; i < va.alive.size(); ++i) {
            if (va.alive[i] && distance(va.position[i], centre) > r_outer)
                peak = std::max(peak, va.height[i] - 0.1);
        }
        EXPECT_GT(peak, 0.8 * expected) << "peak rise " << peak << " m, ring " << expected;
        EXPECT_LT(peak, 1.25 * expected) << "peak rise " << peak << " m, ring " << expected;
        EXPECT_TRUE(mesh_is_sound(tin));
    }
}

TEST(Extrusion, StrokeConservesVolume) {
    const std::vector<Vec2> path = {{0.2, 0.25}, {0.55, 0.4}, {0.7, 0.75}};
    for (const std::string asset : {"circle", "box", "ball", "rake"}) {
        SCOPED_TRACE(asset);
        const Tool tool = Tool::build(spec_of(asset, true));
        Tin tin = terrain();
        SculptContext context(tin.domain());
        StrokeSettings settings;
        settings.spacing = 0.01;
        settings.depth = asset == "ball" ? 0.02 : 0.01;
        settings.depth_mode = DepthMode::Relative;
        const Rect around{{0.05, 0.1}, {0.85, 0.9}};
        const std::vector<Vec2> grid = test::grid_points(around, 801, 801);
        const std::vector<double> h0 = test::surface_at(tin, grid);
        const double v0 = tin.volume();
        std::vector<StampReport> per;
        apply_stroke(tin, tool, path, settings, context, &per);
        EXPECT_TRUE(mesh_is_sound(tin));
        const std::vector<double> h1 = test::surface_at(tin, grid);
        // What the stroke cut, net, on the grid: a lower bound of what it displaced.
        const double cell = (around.width() / 800) * (around.height() / 800);
        double cut = 0.0;
        for (std::size_t i = 0; i < grid.size(); ++i)
            cut += std::max(0.0, h0[i] - h1[i]) * cell;
        ASSERT_GT(cut, 1e-6);
        const double change = tin.volume() - v0;
        EXPECT_LE(std::abs(change), 0.01 * cut) << "net change " << change << " m^3, cut " << cut
                                                << " m^3 over " << per.size() << " stamps";
        EXPECT_NEAR(tin.volume(), test::brute_force_volume(tin), 1e-11);
    }
}

TEST(Extrusion, OnACoarseCurvedTinTheRidgeCarriesTheCut) {
    // An imported elevation model: 400 points over 500 m of rolling hills, so each triangle
    // is tens of metres wide and far from flat. Inserting a 0.5 m tool's rim by Delaunay's rule
    // re-triangulated those triangles, which changed far more volume than the tool cut; the
    // bent edges around the rim are now fenced first (Tin::fence_bent_edges), so it changes
    // next to none. The ridge must hold what the tool cut (the sand above its floor inside the
    // circle, sampled on the terrain before the stamp), and nothing may stick up or down
    // beyond the terrain's own range and the cut.
    Tin tin = test::coarse_hills_model();
    double lo = 1e9, hi = -1e9;
    for (VertexId v : live_ids(tin)) {
        lo = std::min(lo, tin.height(v));
        hi = std::max(hi, tin.height(v));
    }
    SculptContext context(tin.domain());
    ToolSpec spec;
    spec.radius = 0.5;
    spec.extrude = true;
    const Tool tool = Tool::build(spec);
    const Vec2 at{203.0, 207.0};
    const double depth = 0.05;
    const double v0 = tin.volume();
    const double bottom = *tin.height_at(at) - depth;
    double cut = 0.0;
    constexpr int kN = 400;
    const double cell = (1.0 / kN) * (1.0 / kN);
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const Vec2 p{at.x - 0.5 + (i + 0.5) / kN, at.y - 0.5 + (j + 0.5) / kN};
            if (distance(p, at) < 0.5) cut += std::max(0.0, *tin.height_at(p) - bottom) * cell;
        }
    }
    const StampReport r = stamp(tin, tool, {at, 0.0, bottom}, context, Vec2{1.0, 0.0});
    ASSERT_TRUE(r.applied);
    // The fence keeps the re-triangulation to rounding (it was 0.43 m³, seven times the cut).
    EXPECT_GT(r.edges_fenced, 0u);
    EXPECT_LT(std::abs(r.retriangulation_volume), 1e-6 * cut);
    // The band between the contours ramps down to the floor: a little more than the circle.
    EXPECT_GT(r.deposited_volume, 0.98 * cut);
    EXPECT_LT(r.deposited_volume, 1.15 * cut);
    // The cut went into the ridge; the terrain's volume changed by the re-triangulation only.
    EXPECT_NEAR(tin.volume() - v0, r.retriangulation_volume, 1e-9 * std::abs(v0));
    EXPECT_NEAR(r.volume_change, r.retriangulation_volume, 1e-9 * std::abs(v0));
    for (VertexId v : live_ids(tin)) {
        EXPECT_GE(tin.height(v), lo - depth - 1e-6);
        EXPECT_LE(tin.height(v), hi + depth);
    }
    EXPECT_TRUE(mesh_is_sound(tin));
}

TEST(Extrusion, StampAtTheDomainBorderStillConserves) {
    // Moving towards the border or into a corner: most of the ridge, or all of the part the cut
    // depth and the motion favour, would fall outside the domain. Every shipped tool.
    struct Placement {
        Vec2 centre;
        Vec2 motion;
    };
    const Placement placements[] = {
        {{0.03, 0.5}, {-1.0, 0.0}}, {{0.99, 0.01}, {1.0, 0.0}}, {{0.01, 0.99}, {-1.0, 1.0}}};
    for (const char* asset : {"circle", "box", "lambda", "ball", "foot", "rake"}) {
        const Tool tool = Tool::build(spec_of(asset, true));
        for (const Placement& p : placements) {
            SCOPED_TRACE(std::string(asset) + " at " + std::to_string(p.centre.x) + ", " +
                         std::to_string(p.centre.y));
            Tin tin = terrain();
            SculptContext context(tin.domain());
            const ToolPlacement at{p.centre, std::atan2(p.motion.y, p.motion.x),
                                   *tin.height_at(p.centre) - 0.015};
            const double v0 = tin.volume();
            const StampReport r = stamp(tin, tool, at, context, p.motion);
            ASSERT_TRUE(r.applied);
            EXPECT_TRUE(mesh_is_sound(tin));
            ASSERT_GT(r.displaced_volume, 0.0);
            EXPECT_LE(std::abs(tin.volume() - v0), 0.01 * r.displaced_volume);
            EXPECT_NEAR(r.deposited_volume, r.displaced_volume, 0.01 * r.displaced_volume);
            // Part of the band lies in the domain: nothing is lost, and nothing is warned of.
            EXPECT_LE(std::abs(r.undeposited_volume), 1e-9 * r.displaced_volume);
            EXPECT_FALSE(lost_extrusion_warning(r).has_value());
        }
    }
}

// A tool covering the whole terrain has nowhere beside it to push the sand: the band where the
// ridge goes lies outside the domain. That sand leaves the terrain, and the report says how
// much. Oracle: the sand is flat, so the terrain loses the domain's area times the depth, and
// that is what the report must call undeposited.
TEST(Extrusion, ARidgeWithNowhereToGoIsReportedAndWarnedOf) {
    const Rect domain = Rect::from_size(2.0, 1.0);
    Tin tin = Tin::random_points(domain, 2000, 203, [](Vec2) { return 0.1; });
    SculptContext context(domain);
    ToolSpec spec;
    spec.radius = 100.0;
    spec.control_points = 64;
    spec.extrude = true;
    const Tool tool = Tool::build(spec);
    const double v0 = tin.volume();
    const StampReport r = stamp(tin, tool, {{1.0, 0.5}, 0.0, 0.09}, context, Vec2{1.0, 0.0});
    ASSERT_TRUE(r.applied);
    ASSERT_TRUE(mesh_is_sound(tin));
    const double lost = 2.0 * 1.0 * 0.01;
    EXPECT_NEAR(v0 - tin.volume(), lost, 1e-12);
    EXPECT_NEAR(r.undeposited_volume, lost, 1e-12);
    EXPECT_NEAR(r.deposited_volume, 0.0, 1e-12);
    const std::optional<std::string> warning = lost_extrusion_warning(r);
    ASSERT_TRUE(warning.has_value());
    EXPECT_NE(warning->find("nowhere to put 0.02 m³"), std::string::npos) << *warning;
    // Without extrusion nothing was owed, so nothing is lost or warned of.
    Tin plain = Tin::random_points(domain, 2000, 203, [](Vec2) { return 0.1; });
    SculptContext plain_context(domain);
    spec.extrude = false;
    const StampReport q =
        stamp(plain, Tool::build(spec), {{1.0, 0.5}, 0.0, 0.09}, plain_context, Vec2{1.0, 0.0});
    EXPECT_EQ(q.undeposited_volume, 0.0);
    EXPECT_FALSE(lost_extrusion_warning(q).has_value());
}

TEST(Extrusion, DepositRidgeAddsExactlyTheVolumeOutsideTheContour) {
    Tin tin = test::smooth_terrain(test::kUnitSquare, 5000, 202, test::rolling_sand);
    std::vector<Vec2> outer;
    for (Vec2 p : circle_contour(0.05, 24))
        outer.push_back(p + Vec2{0.5, 0.5});
    // Constrained, as a stamp leaves it, so the ridge cannot reach inside.
    const std::vector<VertexId> ids = tin.insert_points_on_surface(outer);
    tin.insert_constraint(ids, /*closed=*/true, 1);
    const std::vector<double> cut(outer.size(), 0.01);
    const double volume = 2e-5;
    const std::vector<Vec2> grid = test::grid_points(Rect{{0.35, 0.35}, {0.65, 0.65}}, 301, 301);
    const std::vector<double> h0 = test::surface_at(tin, grid);
    const double v0 = tin.volume();
    const RidgeReport r = deposit_ridge(tin, outer, cut, Vec2{0.0, 1.0}, 0.04, volume);
    EXPECT_NEAR(tin.volume() - v0, volume, 1e-12 * std::max(1.0, v0));
    EXPECT_NEAR(r.deposited, volume, 1e-15);
    EXPECT_TRUE(mesh_is_sound(tin));
    const std::vector<double> h1 = test::surface_at(tin, grid);
    const Deposit d = deposit_around(grid, h0, h1, 0.001 * 0.001, {0.5, 0.5}, {0.0, 1.0});
    EXPECT_LE(d.rear, 0.05 * d.total);
    // Nothing inside the contour rose.
    for (std::size_t i = 0; i < grid.size(); ++i) {
        if (test::inside_by(grid[i], outer, 1e-9)) {
            EXPECT_LE(h1[i], h0[i] + 1e-12);
        }
    }
    // No volume, no motion, or a zero width: nothing happens.
    const double v1 = tin.volume();
    EXPECT_EQ(deposit_ridge(tin, outer, cut, std::nullopt, 0.04, 0.0).deposited, 0.0);
    EXPECT_EQ(deposit_ridge(tin, outer, cut, std::nullopt, 0.0, 1e-5).deposited, 0.0);
    EXPECT_EQ(tin.volume(), v1);
}

// The ridge raises every vertex outside O within the ridge width of the rim, and no other:
// the set is checked against a brute-force scan of all vertices (point_in_polygon and
// nearest_edge), for a circle and a λ far from the border, a rim within the width of the
// border, and a rim leaving the domain.
TEST(Extrusion, RidgeRaisesExactlyTheVerticesWithinTheWidthOutsideTheRim) {
    const std::vector<Vec2> lambda = {{0.045, -0.05},  {0.025, -0.05},  {0.0, 0.002},
                                      {-0.026, -0.05}, {-0.046, -0.05}, {-0.01, 0.015},
                                      {-0.028, 0.05},  {-0.008, 0.05}};
    struct Case {
        const char* name;
        std::vector<Vec2> outer;
    };
    std::vector<Case> cases;
    auto placed = [](std::vector<Vec2> shape, Vec2 at) {  // counter-clockwise, moved to `at`
        for (Vec2& p : shape)
            p = p + at;
        if (signed_area(shape) < 0.0) std::reverse(shape.begin(), shape.end());
        return shape;
    };
    cases.push_back({"circle", placed(circle_contour(0.05, 48), {0.5, 0.5})});
    cases.push_back({"lambda", placed(lambda, {0.4, 0.6})});
    cases.push_back({"near the border", placed(circle_contour(0.05, 48), {0.5, 0.07})});
    cases.push_back({"across the border", placed(circle_contour(0.05, 48), {0.5, 0.03})});
    const double width = 0.04;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Tin tin = test::smooth_terrain(test::kUnitSquare, 40000, 5, test::rolling_sand);
        const std::vector<double> cut(c.outer.size(), 0.01);
        std::vector<VertexId> touched;
        const RidgeReport r =
            deposit_ridge(tin, c.outer, cut, std::nullopt, width, 1e-5, nullptr, &touched);
        EXPECT_GT(r.deposited, 0.0);
        std::vector<VertexId> expected;
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            if (!point_in_polygon(p, c.outer) && nearest_edge(p, c.outer).distance < width)
                expected.push_back(v);
        }
        std::sort(touched.begin(), touched.end());
        // The band (area pi (0.09² - 0.05²) = 0.0176 m², half of it across the border) holds
        // about 700 of the terrain's 40 000 points, 350 in the last case, besides the stations.
        EXPECT_GT(expected.size(), 300u);
        EXPECT_EQ(touched, expected);
    }
}

// Stations (vertices inserted to carry the ridge) go only where the band lacks vertices: a
// line of four every quarter width of contour, each only where no vertex lies within an
// eighth of the width. Counted on a sparse terrain (they are needed there), on the same
// contour again (the first call's stations are exactly where the second's would go), and on a
// terrain dense enough that every station has a vertex that close (Poisson points of density
// rho leave a disc of radius r empty with probability exp(-rho pi r²), here about 3e-6).
TEST(Extrusion, StationsGoOnlyWhereTheBandLacksVertices) {
    std::vector<Vec2> outer;
    for (Vec2 p : circle_contour(0.05, 200))  // points 1.6 mm apart: far closer than w/4
        outer.push_back(p + Vec2{0.5, 0.5});
    const std::vector<double> cut(outer.size(), 0.01);
    const double width = 0.08;
    const double perimeter = polygon_perimeter(outer);
    const auto max_stations = static_cast<std::size_t>(4.0 * (perimeter / (0.25 * width) + 1.0));
    {
        SCOPED_TRACE("sparse terrain, then the same contour again");
        Tin tin = Tin::random_points(test::kUnitSquare, 400, 11, [](Vec2) { return 0.1; });
        double v0 = tin.volume();
        const RidgeReport first = deposit_ridge(tin, outer, cut, std::nullopt, width, 1e-5);
        EXPECT_GT(first.vertices_inserted, max_stations / 2);  // a sparse band needs them
        EXPECT_LE(first.vertices_inserted, max_stations);
        EXPECT_NEAR(tin.volume() - v0, 1e-5, 1e-15);
        v0 = tin.volume();
        const std::size_t before = tin.vertex_count();
        const RidgeReport second = deposit_ridge(tin, outer, cut, std::nullopt, width, 1e-5);
        EXPECT_EQ(second.vertices_inserted, 0u);
        EXPECT_EQ(tin.vertex_count(), before);
        EXPECT_NEAR(tin.volume() - v0, 1e-5, 1e-15);
        EXPECT_TRUE(mesh_is_sound(tin));
    }
    {
        SCOPED_TRACE("dense terrain");
        Tin tin = Tin::random_points(test::kUnitSquare, 40000, 12, [](Vec2) { return 0.1; });
        const double v0 = tin.volume();
        const RidgeReport r = deposit_ridge(tin, outer, cut, std::nullopt, width, 1e-5);
        EXPECT_EQ(r.vertices_inserted, 0u);
        EXPECT_NEAR(tin.volume() - v0, 1e-5, 1e-15);
    }
}

// On an elevation model whose triangles are tens of metres wide, raising a vertex of the band
// tilted whole triangles: the ridge of a 5 m tool moved the surface 1.7 m, 50 m beyond its band
// (0.5 m tool: 5 cm, 33 m away). The band's outer edge is now constrained at the surface's
// height first (RidgeFence). Oracles: the surface before the stamp, sampled on a grid beyond
// the band (O offset by the ridge width), which may move by no more than the rim tolerance;
// and the volume, which the stamp with extrusion must keep within 1 % of what it displaced.
// The 20 m tool is as wide as the model's triangles: fencing only edges longer than the tool
// left its ridge moving the surface up to 3 m beyond the band.
TEST(Extrusion, OnACoarseElevationModelTheRidgeStaysInItsBand) {
    const Tin model = test::coarse_hills_model();
    const std::vector<Vec2> places = test::coarse_model_placements(model, false);
    for (const double radius : {0.5, 5.0, 20.0}) {
        ToolSpec spec;
        spec.radius = radius;
        spec.extrude = true;
        const Tool tool = Tool::build(spec);
        for (const Vec2 at : places) {
            SCOPED_TRACE(std::to_string(radius) + " m tool at " + std::to_string(at.x) + ", " +
                         std::to_string(at.y));
            Tin tin = Tin::from_snapshot(model.snapshot());
            SculptContext context(tin.domain());
            const double v0 = tin.volume();
            const StampReport r =
                stamp(tin, tool, {at, 0.0, *tin.height_at(at) - 0.05}, context, Vec2{1.0, 0.0});
            ASSERT_TRUE(r.applied);
            ASSERT_TRUE(mesh_is_sound(tin));
            ASSERT_GT(r.displaced_volume, 0.0);
            EXPECT_LE(std::abs(tin.volume() - v0), 0.01 * r.displaced_volume);
            EXPECT_NEAR(r.deposited_volume, r.displaced_volume, 0.01 * r.displaced_volume);
            const std::vector<Vec2> band = offset_contour(
                test::rotate_all(tool.shape().outer, at, 0.0), tool.extrusion_width());
            double worst = 0.0;
            Vec2 worst_at;
            LocateHint before_hint, after_hint;
            // Far enough out for the reach the unfenced edges had (up to three radii beyond O).
            const double reach = 60.0 + 3.0 * radius;
            for (Vec2 p : test::grid_points(Rect{at - Vec2{reach, reach}, at + Vec2{reach, reach}},
                                            241, 241)) {
                if (!model.domain().contains(p) || !test::outside_by(p, band, 1e-3)) continue;
                const double d =
                    std::abs(*tin.height_at(p, &after_hint) - *model.height_at(p, &before_hint));
                if (d > worst) worst_at = p;
                worst = std::max(worst, d);
            }
            EXPECT_LE(worst, tool.rim_tolerance())
                << "the surface moved beyond the ridge's band by " << worst << " m at "
                << worst_at.x << ", " << worst_at.y;
        }
    }
}

/// Where the surface rose along the ridge's crest: the points half the width w outside the
/// counter-clockwise polygon `outer` (three per edge, stepped out along the edge's normal, kept
/// only where that edge is the nearest: not in a concavity another edge is closer to).
std::vector<double> crest_rise(const Tin& tin, std::span<const Vec2> outer, double w,
                               double level) {
    std::vector<double> rise;
    LocateHint hint;
    for (std::size_t i = 0; i < outer.size(); ++i) {
        const Vec2 a = outer[i];
        const Vec2 b = outer[(i + 1) % outer.size()];
        const Vec2 e = (b - a) / length(b - a);
        for (const double t : {0.25, 0.5, 0.75}) {
            const Vec2 p = lerp(a, b, t) + Vec2{e.y, -e.x} * (0.5 * w);
            if (std::abs(test::distance_to_border(p, outer) - 0.5 * w) > 1e-9 * w) continue;
            rise.push_back(*tin.height_at(p, &hint) - level);
        }
    }
    return rise;
}

/// The peak of a ridge that carries `volume` with the documented cross-section
/// 1 - (2s/w - 1)² at every point of the band (s < w outside `outer`) and an even weight: the
/// volume over the cross-section's integral, taken on a grid of the band's plane.
double even_ridge_height(std::span<const Vec2> outer, double w, double volume) {
    Rect box;
    for (Vec2 p : outer)
        box.expand(p);
    const Rect band{box.min - Vec2{w, w}, box.max + Vec2{w, w}};
    constexpr int kN = 500;
    const double cell = (band.width() / kN) * (band.height() / kN);
    double integral = 0.0;
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const Vec2 p{band.min.x + band.width() * (i + 0.5) / kN,
                         band.min.y + band.height() * (j + 0.5) / kN};
            if (test::inside_polygon(p, outer)) continue;
            const double s = test::distance_to_border(p, outer);
            if (s >= w) continue;
            const double t = 2.0 * s / w - 1.0;
            integral += (1.0 - t * t) * cell;
        }
    }
    return volume / integral;
}

// The foot, pressed without motion deep enough that its whole outline cuts the sand, puts the
// sand back in a ridge that follows the sole, as the circle's does. It used to heap it in a
// sunburst: 7-8 radial stripes the band's length (13 cm), with nothing between them (the
// crest's lowest point at the flat level) and a peak three times the even ridge's height, since
// the profile read "no contact" at most outline points and the ridge was weighted point by
// point. Oracles: the flat level; the even ridge of the documented cross-section holding the
// displaced volume (its cut varies along the sole, 4-17 mm, so the ridge may not be even: it
// must stay within half and one and a half times the even ridge's height); the band's width
// (beyond it nothing rises); and the volume, exactly the same before and after.
TEST(Extrusion, TheFootsRidgeFollowsTheSole) {
    const Tool tool = Tool::build(spec_of("foot", true));
    const double w = tool.extrusion_width();
    const double level = 0.1;
    const double depth = 0.025;
    for (const double angle : {0.0, 0.7, 2.0}) {
        SCOPED_TRACE("angle " + std::to_string(angle));
        Tin tin = Tin::random_points(test::kUnitSquare, 40000, 31, [=](Vec2) { return level; });
        SculptContext context(tin.domain());
        const ToolPlacement at{{0.5, 0.5}, angle, level - depth};
        const double v0 = tin.volume();
        const StampReport r = stamp(tin, tool, at, context);
        ASSERT_TRUE(r.applied);
        EXPECT_TRUE(mesh_is_sound(tin));
        ASSERT_GT(r.displaced_volume, 1e-5);
        EXPECT_NEAR(tin.volume(), v0, 1e-12 * v0);
        EXPECT_NEAR(r.deposited_volume, r.displaced_volume, 1e-9 * r.displaced_volume);
        const std::vector<Vec2> outer = test::rotate_all(tool.shape().outer, at.centre, angle);
        const double even = even_ridge_height(outer, w, r.displaced_volume);
        const std::vector<double> crest = crest_rise(tin, outer, w, level);
        ASSERT_GT(crest.size(), 100u);
        const double lowest = *std::min_element(crest.begin(), crest.end());
        EXPECT_GE(lowest, 0.5 * even) << "a gap in the ridge; the even ridge is " << even << " m";
        double highest = 0.0;
        std::size_t beyond = 0;
        for (VertexId v : live_ids(tin)) {
            const Vec2 p = tin.position(v);
            if (inside_polygon(p, outer)) continue;
            highest = std::max(highest, tin.height(v) - level);
            if (test::distance_to_border(p, outer) > w + 1e-9 && tin.height(v) != level) ++beyond;
        }
        EXPECT_LE(highest, 1.5 * even) << "a spike; the even ridge is " << even << " m";
        EXPECT_EQ(beyond, 0u) << "vertices moved beyond the band";
    }
}

// deposit_ridge weights the ridge by the cut at each contour point. A ridge as wide as the band
// cannot follow a cut that changes from one point to the next: given a cut of 0 and 1 cm at
// alternate points of a circle, it raised radial stripes (the crest at the flat level between
// them). The cut is now averaged along the contour, so the ridge is the even ring. Oracle: the
// analytic ring of the documented cross-section, V = H 2 pi (2 w R / 3 + w² / 3), on flat sand.
TEST(Extrusion, ACutThatAlternatesAlongTheContourGivesAnEvenRidge) {
    const double level = 0.1;
    Tin tin = Tin::random_points(test::kUnitSquare, 40000, 37, [=](Vec2) { return level; });
    const double radius = 0.05;
    std::vector<Vec2> outer;
    for (Vec2 p : circle_contour(radius, 48))
        outer.push_back(p + Vec2{0.5, 0.5});
    std::vector<double> cut(outer.size());
    for (std::size_t i = 0; i < cut.size(); ++i)
        cut[i] = i % 2 == 0 ? 0.01 : 0.0;
    const double w = 0.04;
    const double volume = 2e-5;
    const double v0 = tin.volume();
    const RidgeReport r = deposit_ridge(tin, outer, cut, std::nullopt, w, volume);
    EXPECT_NEAR(r.deposited, volume, 1e-15);
    EXPECT_NEAR(tin.volume() - v0, volume, 1e-12 * v0);
    EXPECT_TRUE(mesh_is_sound(tin));
    const double ring = volume / (2.0 * std::numbers::pi * (2.0 * w * radius / 3.0 + w * w / 3.0));
    const std::vector<double> crest = crest_rise(tin, outer, w, level);
    ASSERT_EQ(crest.size(), 3 * outer.size());
    const auto [lowest, highest] = std::minmax_element(crest.begin(), crest.end());
    EXPECT_GE(*lowest, 0.8 * ring) << "the even ring is " << ring << " m high";
    EXPECT_LE(*highest, 1.2 * ring) << "the even ring is " << ring << " m high";
}

}  // namespace
}  // namespace sandtin
