// insert_point and insert_point_on_surface.
// Oracles: Euler's formula, the plane itself, brute-force interpolation in the triangle that
// contains the point (found over triangles()), and the volume before/after.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::brute_force_volume;
using test::close_rel;
using test::Plane;

double wavy(Vec2 p) {
    return 2.0 + 0.4 * std::sin(1.7 * p.x + 0.3) * std::cos(1.1 * p.y) + 0.05 * p.x * p.y;
}

TEST(InsertPoint, InteriorPointGetsGivenHeightAndTwoMoreTriangles) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 40, 1, wavy);
    const std::size_t v0 = tin.vertex_count();
    const std::size_t t0 = tin.triangle_count();
    const Vec2 p{1.2345, 2.71828};
    const VertexId v = tin.insert_point(p, -3.5);
    ASSERT_TRUE(tin.is_alive(v));
    EXPECT_EQ(tin.position(v), p);
    EXPECT_EQ(tin.height(v), -3.5);
    EXPECT_EQ(tin.vertex_count(), v0 + 1);
    EXPECT_EQ(tin.triangle_count(), t0 + 2);
    EXPECT_FALSE(tin.is_boundary(v));
    const auto loc = tin.locate(p);
    EXPECT_EQ(loc.kind, Location::Kind::OnVertex);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertPoint, BorderPointAddsOneTriangle) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(4.0, 2.0), 1.0);
    const VertexId v = tin.insert_point({1.5, 0.0}, 1.0);
    EXPECT_TRUE(tin.is_boundary(v));
    EXPECT_EQ(tin.vertex_count(), 5u);
    EXPECT_EQ(tin.triangle_count(), 3u);  // Euler: 2*5 - 5 - 2
    const VertexId w = tin.insert_point({4.0, 0.5}, 1.0);
    EXPECT_TRUE(tin.is_boundary(w));
    EXPECT_EQ(tin.triangle_count(), 4u);
    // Flat at 1 everywhere: volume is the area.
    EXPECT_TRUE(close_rel(tin.volume(), 8.0, 1e-14));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertPoint, DuplicatePositionReturnsSameIdAndSetsHeight) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 40, 2, wavy);
    const Vec2 p{2.5, 0.75};
    const VertexId v = tin.insert_point(p, 1.0);
    const std::size_t n = tin.vertex_count();
    const std::size_t t = tin.triangle_count();
    const VertexId again = tin.insert_point(p, 7.25);
    EXPECT_EQ(again, v);
    EXPECT_EQ(tin.height(v), 7.25);
    EXPECT_EQ(tin.vertex_count(), n);
    EXPECT_EQ(tin.triangle_count(), t);
    // Same for a corner created by the constructor.
    const VertexId corner = tin.insert_point({4.0, 4.0}, -2.0);
    EXPECT_EQ(tin.position(corner), (Vec2{4.0, 4.0}));
    EXPECT_EQ(tin.height(corner), -2.0);
    EXPECT_EQ(tin.vertex_count(), n);
    EXPECT_TRUE(close_rel(tin.volume(), brute_force_volume(tin), 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertPoint, RejectsOutsideAndNonFiniteWithoutChangingAnything) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 30, 3, wavy);
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    EXPECT_THROW(tin.insert_point({4.0000001, 1.0}, 0.0), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({-1e-12, 1.0}, 0.0), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({1.0, 100.0}, 0.0), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({test::kNaN, 1.0}, 0.0), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({1.0, test::kInf}, 0.0), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({1.0, 1.0}, test::kNaN), std::invalid_argument);
    EXPECT_THROW(tin.insert_point({1.0, 1.0}, test::kInf), std::invalid_argument);
    EXPECT_THROW(tin.insert_point_on_surface({5.0, 1.0}), std::invalid_argument);
    EXPECT_THROW(tin.insert_point_on_surface({test::kNaN, test::kNaN}), std::invalid_argument);
    try {
        tin.insert_point({9.0, 1.0}, 0.0);
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("outside"), std::string::npos) << e.what();
    }
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(InsertPoint, ReportedVolumeChangeEqualsMeasuredChange) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 4, wavy);
    std::mt19937_64 rng = test::test_rng(4);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    for (int i = 0; i < 200; ++i) {
        const Vec2 p{u(rng), u(rng)};
        const double before = tin.volume();
        EditReport report;
        tin.insert_point(p, u(rng), nullptr, &report);
        const double after = tin.volume();
        EXPECT_NEAR(report.volume_change, after - before, 1e-12 * std::abs(before));
        EXPECT_EQ(report.vertices_created, 1u);
        EXPECT_EQ(report.vertices_removed, 0u);
        EXPECT_GE(report.triangles_changed, 3u);  // at least the three new triangles
    }
    EXPECT_TRUE(close_rel(tin.volume(), brute_force_volume(tin), 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertPoint, HeightBelowBedrockKeepsBedrockUnderTheSurface) {
    // Bedrock is the non-erodible floor (<= height, an invariant of check_valid). A point
    // inserted below the interpolated bedrock must not leave the floor above the surface.
    Tin tin = Tin::flat_rectangle(Rect::from_size(10.0, 10.0), 1.0);
    for (VertexId v : test::live_ids(tin))
        tin.set_bedrock(v, 0.5);
    const VertexId v = tin.insert_point({3.0, 4.0}, 0.2);
    EXPECT_EQ(tin.height(v), 0.2);
    EXPECT_LE(tin.vertices().bedrock[v.index()], tin.height(v));
    const ValidationReport r = tin.check_valid();
    EXPECT_TRUE(r.ok()) << r.summary();
    // The same through set_height.
    tin.set_height(v, 0.1);
    EXPECT_LE(tin.vertices().bedrock[v.index()], tin.height(v));
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(InsertOnSurface, PlanarSurfaceGivesPlaneHeightExactly) {
    const Rect d{{-2.0, -1.0}, {3.0, 4.0}};
    const Plane plane{0.75, -0.3, 1.5};
    Tin tin = Tin::random_points(d, 100, 8, plane);
    std::mt19937_64 rng = test::test_rng(8);
    std::uniform_real_distribution<double> ux(d.min.x, d.max.x);
    std::uniform_real_distribution<double> uy(d.min.y, d.max.y);
    LocateHint hint;
    for (int i = 0; i < 500; ++i) {
        const Vec2 p{ux(rng), uy(rng)};
        const VertexId v = tin.insert_point_on_surface(p, i % 2 ? &hint : nullptr);
        EXPECT_NEAR(tin.height(v), plane(p), 1e-12 * (1.0 + std::abs(plane(p))));
    }
    // Every vertex, old and new, still lies on the plane; the volume is the plane's integral.
    for (VertexId v : test::live_ids(tin)) {
        EXPECT_NEAR(tin.height(v), plane(tin.position(v)), 1e-12 * 4.0);
    }
    EXPECT_TRUE(close_rel(tin.volume(), plane.integral(d), 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertOnSurface, ReportPolicyHeightIsBruteForceInterpolation) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 150, 9, wavy);
    std::mt19937_64 rng = test::test_rng(9);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    for (int i = 0; i < 150; ++i) {
        const Vec2 p{u(rng), u(rng)};
        const double expected = test::brute_force_height(tin, p);
        const VertexId v = tin.insert_point_on_surface(p, nullptr, VolumePolicy::Report);
        EXPECT_NEAR(tin.height(v), expected, 1e-12 * 3.0) << i;
    }
}

TEST(InsertOnSurface, VolumeUnchangedOnCurvedSurface) {
    // Acceptance: volume is unchanged, to 1e-12 relative, after inserting points at their
    // interpolated heights.
    for (std::uint64_t seed : {11u, 12u, 13u}) {
        SCOPED_TRACE(seed);
        const Rect d = Rect::from_size(6.0, 4.0);
        Tin tin = Tin::random_points(d, 300, seed, [](Vec2 p) {
            // Random-looking, strongly curved heights.
            return 1.0 + 0.5 * std::sin(5.1 * p.x) * std::sin(4.3 * p.y) +
                   0.2 * std::cos(9.7 * p.x * p.y);
        });
        const double v0 = tin.volume();
        std::mt19937_64 rng = test::test_rng(seed);
        std::uniform_real_distribution<double> ux(0.0, 6.0);
        std::uniform_real_distribution<double> uy(0.0, 4.0);
        LocateHint hint;
        double worst = 0.0;
        for (int i = 0; i < 2000; ++i) {
            const double before = tin.volume();
            const Vec2 p =
                i % 50 == 0 ? Vec2{ux(rng), 0.0} : Vec2{ux(rng), uy(rng)};  // some on the border
            tin.insert_point_on_surface(p, &hint);
            worst = std::max(worst, std::abs(tin.volume() - before) / std::abs(before));
        }
        EXPECT_LE(worst, 1e-12) << "largest relative volume change of one insertion";
        EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * std::abs(v0))
            << "volume drifted from " << v0 << " to " << tin.volume();
        EXPECT_TRUE(close_rel(brute_force_volume(tin), v0, 1e-12));
        EXPECT_TRUE(test::tin_is_sound(tin));
    }
}

TEST(InsertOnSurface, ReportPolicyVolumeChangeEqualsMeasuredDifference) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 300, 21, [](Vec2 p) {
        return 1.0 + 0.5 * std::sin(6.0 * p.x) * std::cos(5.0 * p.y);
    });
    std::mt19937_64 rng = test::test_rng(21);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    double total_reported = 0.0;
    const double v0 = tin.volume();
    bool any_nonzero = false;
    for (int i = 0; i < 500; ++i) {
        const double before = tin.volume();
        EditReport report;
        tin.insert_point_on_surface({u(rng), u(rng)}, nullptr, VolumePolicy::Report, &report);
        const double after = tin.volume();
        EXPECT_NEAR(report.volume_change, after - before, 1e-12 * std::abs(before)) << i;
        total_reported += report.volume_change;
        any_nonzero = any_nonzero || report.volume_change != 0.0;
    }
    // Flips on a curved surface do change the volume, and the reports add up.
    EXPECT_TRUE(any_nonzero);
    EXPECT_NEAR(total_reported, tin.volume() - v0, 1e-11 * std::abs(v0));
    EXPECT_TRUE(close_rel(tin.volume(), brute_force_volume(tin), 1e-12));
}

TEST(InsertOnSurface, ExistingPositionReturnsExistingVertexUnchanged) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 30, 5, wavy);
    const VertexId v = tin.insert_point({1.0, 1.0}, 5.0);
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    LocateHint hint;
    EXPECT_EQ(tin.insert_point_on_surface({1.0, 1.0}, &hint), v);
    EXPECT_EQ(hint.vertex, v);
    EXPECT_EQ(tin.height(v), 5.0);
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(InsertOnSurface, HintIsUpdatedToTheNewVertex) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 100, 6, wavy);
    LocateHint hint;
    const VertexId v = tin.insert_point_on_surface({2.2, 3.3}, &hint);
    EXPECT_EQ(hint.vertex, v);
    const VertexId w = tin.insert_point({0.2, 0.3}, 1.0, &hint);
    EXPECT_EQ(hint.vertex, w);
    // A stale (dead) hint is ignored.
    ASSERT_TRUE(tin.remove_vertex(w));
    const VertexId x = tin.insert_point_on_surface({3.9, 0.1}, &hint);
    EXPECT_TRUE(tin.is_alive(x));
    EXPECT_EQ(tin.position(x), (Vec2{3.9, 0.1}));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(InsertOnSurface, NewVertexInheritsInterpolatedAttributes) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(2.0, 2.0), 1.0);
    for (VertexId v : test::live_ids(tin)) {
        tin.set_moisture(v, 0.5f);
        tin.set_bedrock(v, 0.25);
        tin.set_material(v, 7);
        tin.set_water_depth(v, 0.04 * (1.0 + tin.position(v).x));  // linear in x
    }
    const VertexId v = tin.insert_point_on_surface({0.7, 0.6});
    // Water depth, like moisture, interpolates linearly: exact for a linear field.
    EXPECT_NEAR(tin.vertices().water_depth[v.index()], 0.04 * 1.7, 1e-15);
    EXPECT_FLOAT_EQ(tin.vertices().moisture[v.index()], 0.5f);
    EXPECT_NEAR(tin.vertices().bedrock[v.index()], 0.25, 1e-15);
    EXPECT_EQ(tin.vertices().material[v.index()], 7);
    EXPECT_NEAR(tin.height(v), 1.0, 1e-15);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

}  // namespace
}  // namespace sandtin
