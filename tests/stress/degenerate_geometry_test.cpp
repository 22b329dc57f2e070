// Degenerate geometry (issue 9 §2): every case keeps a valid mesh (CGAL's own check plus the
// stress invariants) or is rejected with a message naming the problem; nothing crashes, hangs
// or corrupts the terrain. Oracles: Euler's formula for triangle counts, exact volumes of flat
// terrains, the volume ledger against a from-scratch volume, byte-equal snapshots for no-ops.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/session_file.hpp"
#include "stress/terrain_invariants.hpp"
#include "tin/tin.hpp"
#include "tools/sculpt_context.hpp"
#include "tools/stamp.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"

namespace sandtin {
namespace {

void expect_sound(const Tin& tin, Generation next_generation = 1 << 30) {
    const auto v = check_terrain_invariants(tin, next_generation, {});
    EXPECT_FALSE(v.has_value()) << v->invariant << ": " << v->detail;
}

/// Triangles of a triangulated convex domain with n vertices, h of them on the hull border
/// (collinear border points count: they are vertices of the border polygon).
std::size_t euler_triangles(std::size_t n, std::size_t h) {
    return 2 * n - h - 2;
}

Tool circle(double radius, int control_points = 12) {
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = radius;
    spec.control_points = control_points;
    return Tool::build(spec);
}

std::vector<std::uint8_t> bytes_of(const Tin& tin) {
    Session s;
    s.terrain = tin.snapshot();
    return encode_session(s);
}

TEST(DegenerateGeometry, CollinearPointsInsideTheDomain) {
    const Rect d = Rect::from_size(1.0, 1.0);
    std::vector<Vec2> pts;
    std::vector<double> hs;
    for (int i = 1; i < 500; ++i) {
        pts.push_back({i / 500.0, i / 500.0});  // on the diagonal, exactly collinear
        hs.push_back(0.1);
    }
    const Tin tin = Tin::from_points(d, pts, hs);
    expect_sound(tin);
    EXPECT_EQ(tin.vertex_count(), 499u + 4u);
    EXPECT_EQ(tin.triangle_count(), euler_triangles(503, 4));
}

TEST(DegenerateGeometry, CocircularPointsAndTheirCentre) {
    const Rect d = Rect::from_size(2.0, 2.0);
    std::vector<Vec2> pts = {{1.0, 1.0}};
    std::vector<double> hs = {0.5};
    for (int k = 0; k < 256; ++k) {
        const double a = 2.0 * std::numbers::pi * k / 256.0;
        pts.push_back({1.0 + 0.75 * std::cos(a), 1.0 + 0.75 * std::sin(a)});
        hs.push_back(0.5);
    }
    const Tin tin = Tin::from_points(d, pts, hs);
    expect_sound(tin);
    EXPECT_EQ(tin.triangle_count(), euler_triangles(tin.vertex_count(), 4));
    // Flat at 0.5 m over 4 m²: the volume is exact whatever the (ambiguous) diagonals.
    EXPECT_NEAR(tin.volume(), 2.0, 1e-12);
}

TEST(DegenerateGeometry, ExactRegularGridWhereEveryQuadIsCocircular) {
    const Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 150, 150);
    expect_sound(tin);
    EXPECT_EQ(tin.vertex_count(), 151u * 151u);
    EXPECT_EQ(tin.triangle_count(), 2u * 150u * 150u);
}

TEST(DegenerateGeometry, PointsATrillionthOfAMetreApartDoNotSplitTheMesh) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 300, 8);
    const std::size_t before = tin.vertex_count();
    const VertexId a = tin.insert_point({0.5, 0.5}, 0.2);
    const VertexId b = tin.insert_point({0.5 + 1e-12, 0.5}, 0.3);
    const VertexId c = tin.insert_point({0.5, 0.5 + 1e-12}, 0.25);
    expect_sound(tin);
    // Within the snap distance: the later points land on the first vertex (or are merged), so
    // at most one vertex is added and no sliver of 1e-12 m exists.
    EXPECT_LE(tin.vertex_count(), before + 1);
    EXPECT_TRUE(tin.is_alive(a));
    (void)b;
    (void)c;
}

TEST(DegenerateGeometry, MillimetreFeaturesAtMillionMetreCoordinates) {
    // A 20 m tile of a survey grid in a projected CRS: eastings ~1e6 m, northings ~2e6 m.
    const Rect d{{1.0e6, 2.0e6}, {1.0e6 + 20.0, 2.0e6 + 20.0}};
    Tin tin = Tin::random_points(d, 2000, 9, [](Vec2) { return 100.0; });
    SculptContext ctx(d);
    const double v0 = tin.volume(100.0);
    const Vec2 c{1.0e6 + 10.0, 2.0e6 + 10.0};
    // A 5 mm radius tool pressed 2 mm deep.
    const StampReport r = stamp(tin, circle(0.005), {c, 0.3, 100.0 - 0.002}, ctx);
    expect_sound(tin, ctx.peek_generation());
    ASSERT_TRUE(r.applied);
    const double floor = tin.height_at(c).value();
    EXPECT_NEAR(floor, 100.0 - 0.002, 1e-9);
    EXPECT_NEAR(tin.height_at(c + Vec2{0.02, 0.0}).value(), 100.0, 1e-9);
    // The volume the stamp reported is what the terrain lost (a ~1.6e-7 m³ dent).
    EXPECT_NEAR(tin.volume(100.0) - v0, r.volume_change, 1e-12);
    EXPECT_LT(r.volume_change, -1e-7);
}

TEST(DegenerateGeometry, ZeroRadiusToolIsRejectedByName) {
    try {
        circle(0.0);
        FAIL() << "a zero-radius tool was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos) << e.what();
    }
}

TEST(DegenerateGeometry, ZeroDepthStampOnFlatSandChangesNoVolume) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 500, 10, [](Vec2) { return 0.1; });
    SculptContext ctx(tin.domain());
    const double v0 = tin.volume();
    const StampReport r = stamp(tin, circle(0.05), {{0.5, 0.5}, 0.0, 0.1}, ctx);
    expect_sound(tin, ctx.peek_generation());
    EXPECT_NEAR(r.volume_change, 0.0, 1e-15);
    EXPECT_NEAR(tin.volume(), v0, 1e-14);
}

TEST(DegenerateGeometry, SelfIntersectingContourIsRejectedByName) {
    ToolSpec spec;
    spec.contour = ContourKind::Polygon;
    spec.polygon = {{-1, -1}, {1, 1}, {1, -1}, {-1, 1}};  // a bow tie
    spec.scale = 0.02;
    try {
        Tool::build(spec);
        FAIL() << "a self-intersecting contour was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("simple"), std::string::npos) << e.what();
    }
}

TEST(DegenerateGeometry, ToolPartlyOutsideTheDomainCutsOnlyTheInside) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 800, 12, [](Vec2) { return 0.1; });
    SculptContext ctx(tin.domain());
    const double v0 = tin.volume();
    // Centred on the corner: a quarter of the disc lies over the terrain.
    const StampReport r = stamp(tin, circle(0.1, 24), {{0.0, 0.0}, 0.0, 0.05}, ctx);
    expect_sound(tin, ctx.peek_generation());
    ASSERT_TRUE(r.applied);
    EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-12);
    // About a quarter of a 0.1 m disc, 5 cm deep (the rim gap makes it a little larger).
    const double quarter = 0.25 * std::numbers::pi * 0.01 * 0.05;
    EXPECT_GT(-r.volume_change, 0.8 * quarter);
    EXPECT_LT(-r.volume_change, 1.3 * quarter);
    EXPECT_NEAR(tin.height_at({0.01, 0.01}).value(), 0.05, 1e-12);
}

TEST(DegenerateGeometry, ToolWhollyOutsideTheDomainChangesNothing) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 300, 13, [](Vec2) { return 0.1; });
    SculptContext ctx(tin.domain());
    const std::vector<std::uint8_t> before = bytes_of(tin);
    const StampReport r = stamp(tin, circle(0.1), {{3.0, -2.0}, 0.0, 0.0}, ctx);
    EXPECT_FALSE(r.applied);
    EXPECT_EQ(bytes_of(tin), before);
}

TEST(DegenerateGeometry, StrokeExactlyAlongAnExistingConstraint) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 1000, 14, [](Vec2) { return 0.1; });
    SculptContext ctx(tin.domain());
    stamp(tin, circle(0.1, 16), {{0.5, 0.5}, 0.0, 0.08}, ctx);
    const std::vector<ConstraintInfo> all = tin.constraints();
    ASSERT_FALSE(all.empty());
    // Follow the first rim constraints exactly, through their vertices.
    std::vector<Vec2> path;
    for (std::size_t i = 0; i < std::min<std::size_t>(all.size(), 8); ++i) {
        for (VertexId v : all[i].vertices)
            path.push_back(tin.position(v));
    }
    const double v0 = tin.volume();
    StrokeSettings s;
    s.spacing = 0.01;
    s.depth = 0.01;
    const StampReport r = apply_stroke(tin, circle(0.02), path, s, ctx);
    expect_sound(tin, ctx.peek_generation());
    EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-12);
}

TEST(DegenerateGeometry, StrokeCrossingManyOldConstraints) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 500, 15, [](Vec2) { return 0.1; });
    SculptContext ctx(tin.domain());
    // Sixty thin rectangles side by side leave about 240 rim constraints across the path.
    ToolSpec bar;
    bar.contour = ContourKind::Rectangle;
    bar.width = 0.6;
    bar.length = 0.004;
    const Tool bar_tool = Tool::build(bar);
    for (int k = 0; k < 60; ++k)
        stamp(tin, bar_tool, {{0.1 + k * 0.0133, 0.5}, 0.0, 0.095}, ctx);
    expect_sound(tin, ctx.peek_generation());
    const std::size_t constraints_before = tin.constraint_count();
    const double v0 = tin.volume();
    StrokeSettings s;
    s.spacing = 0.005;
    s.depth = 0.02;
    const std::vector<Vec2> across = {{0.02, 0.5}, {0.98, 0.52}};
    const StampReport r = apply_stroke(tin, circle(0.03), across, s, ctx);
    expect_sound(tin, ctx.peek_generation());
    EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-11);
    EXPECT_GT(r.constraints_released, 0u);
    // Bounded by the generations kept, not by the stamps: a stroke keeps at most the rims of
    // its last keep_generations stamps (each measured alone on a fresh terrain) plus the old
    // constraints, which it can only release or split, plus the edges it fenced: the bars'
    // long, bent edges, which guard their imprints beside the stroke (Tin::fence_bent_edges;
    // each is fenced once, and the stroke's later stamps do not fence them again).
    Tin fresh = Tin::flat_rectangle(Rect::from_size(1.0, 1.0), 0.1);
    SculptContext fresh_ctx(fresh.domain());
    stamp(fresh, circle(0.03), {{0.5, 0.5}, 0.0, 0.08}, fresh_ctx);
    const std::size_t per_stamp = fresh.constraint_count();
    ASSERT_GT(per_stamp, 0u);
    EXPECT_LE(
        tin.constraint_count(),
        constraints_before + (ctx.settings.keep_generations + 1) * per_stamp + r.edges_fenced);
    EXPECT_LT(r.edges_fenced, constraints_before / 4) << "fences grew with the stamps";
}

}  // namespace
}  // namespace sandtin
