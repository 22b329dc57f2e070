// remove_vertex. Oracles: Euler's formula, volume before/after (conserved or reported),
// brute-force volume, snapshot equality when nothing may change.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::brute_force_volume;
using test::close_rel;

double bumpy(Vec2 p) {
    return 3.0 + 0.6 * std::sin(4.0 * p.x) * std::cos(3.0 * p.y) - 0.1 * p.y;
}

std::vector<VertexId> interior_ids(const Tin& tin) {
    std::vector<VertexId> out;
    for (VertexId v : test::live_ids(tin)) {
        if (!test::on_domain_border(tin.domain(), tin.position(v))) out.push_back(v);
    }
    return out;
}

TEST(RemoveVertex, InteriorVertexDisappearsAndEulerHolds) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 100, 1, bumpy);
    const auto ids = interior_ids(tin);
    const VertexId v = ids[ids.size() / 2];
    const Vec2 p = tin.position(v);
    const std::size_t n = tin.vertex_count();
    const std::size_t t = tin.triangle_count();
    EXPECT_TRUE(tin.remove_vertex(v));
    EXPECT_FALSE(tin.is_alive(v));
    EXPECT_EQ(tin.vertices().alive[v.index()], 0);
    EXPECT_EQ(tin.vertex_count(), n - 1);
    EXPECT_EQ(tin.triangle_count(), t - 2);
    EXPECT_NE(tin.locate(p).kind, Location::Kind::OnVertex);
    for (const auto& tri : tin.triangles()) {
        for (VertexId c : tri)
            EXPECT_NE(c, v);
    }
    // A dead id cannot be removed again, nor queried.
    EXPECT_THROW(tin.remove_vertex(v), std::invalid_argument);
    EXPECT_THROW((void)tin.height(v), std::invalid_argument);
    EXPECT_THROW((void)tin.position(v), std::invalid_argument);
    EXPECT_THROW(tin.remove_vertex(VertexId{}), std::invalid_argument);
    EXPECT_THROW(tin.remove_vertex(VertexId{tin.vertex_capacity() + 10}), std::invalid_argument);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveVertex, BorderVerticesAreRefusedAndNothingChanges) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 50, 2, bumpy);
    const VertexId mid_edge = tin.insert_point({2.0, 0.0}, 1.0);
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    std::size_t border = 0;
    for (VertexId v : test::live_ids(tin)) {
        if (!test::on_domain_border(tin.domain(), tin.position(v))) continue;
        ++border;
        EXPECT_TRUE(tin.is_boundary(v));
        EditReport report;
        EXPECT_FALSE(tin.remove_vertex(v, VolumePolicy::Conserve, &report));
        EXPECT_EQ(report.vertices_removed, 0u);
        EXPECT_EQ(report.volume_change, 0.0);
    }
    EXPECT_EQ(border, 5u);  // four corners and the one on the bottom edge
    EXPECT_TRUE(tin.is_alive(mid_edge));
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(RemoveVertex, ConstrainedVerticesAreRefused) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 50, 3, bumpy);
    const VertexId a = tin.insert_point({1.0, 1.0}, 1.0);
    const VertexId b = tin.insert_point({3.0, 2.5}, 2.0);
    const VertexId c = tin.insert_point({2.0, 3.0}, 1.5);
    tin.insert_constraint(a, b, 1);
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    EXPECT_TRUE(tin.is_on_constraint(a));
    EXPECT_TRUE(tin.is_on_constraint(b));
    EXPECT_FALSE(tin.remove_vertex(a));
    EXPECT_FALSE(tin.remove_vertex(b));
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_FALSE(tin.is_on_constraint(c));
    EXPECT_TRUE(tin.remove_vertex(c));
    // Once the constraint is released, its vertices can go.
    ASSERT_EQ(tin.release_constraints({}), 1u);
    EXPECT_FALSE(tin.is_on_constraint(a));
    EXPECT_TRUE(tin.remove_vertex(a));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveVertex, ConservePolicyKeepsVolume) {
    for (std::uint64_t seed : {4u, 5u}) {
        SCOPED_TRACE(seed);
        Tin tin = Tin::random_points(Rect::from_size(5.0, 3.0), 800, seed, bumpy);
        const double v0 = tin.volume();
        auto ids = interior_ids(tin);
        std::mt19937_64 rng = test::test_rng(seed);
        std::shuffle(ids.begin(), ids.end(), rng);
        ids.resize(600);
        double worst = 0.0;
        for (VertexId v : ids) {
            const double before = tin.volume();
            EditReport report;
            ASSERT_TRUE(tin.remove_vertex(v, VolumePolicy::Conserve, &report));
            EXPECT_EQ(report.vertices_removed, 1u);
            worst = std::max(worst, std::abs(tin.volume() - before) / std::abs(before));
        }
        EXPECT_LE(worst, 1e-12);
        EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * std::abs(v0));
        EXPECT_TRUE(close_rel(brute_force_volume(tin), v0, 1e-12));
        EXPECT_EQ(tin.vertex_count(), 804u - 600u);
        EXPECT_TRUE(test::tin_is_sound(tin));
    }
}

// Two vertices closer than the snap distance (left where nearly coincident rims crossed) must
// keep one height, or the sliver between them is a vertical wall. A removal's compensation
// shifts the removed vertex's ring; a ring vertex with such a twin outside the ring meets it at
// their area-weighted mean, which moves no volume.
TEST(RemoveVertex, ConserveShiftKeepsTwinsWithinTheSnapDistanceLevel) {
    const Rect domain = Rect::from_size(4.0, 4.0);
    const Vec2 centre{2.0, 2.0};
    const Vec2 ring_point{2.3, 2.0};
    // Beyond ring_point as seen from the centre, so not a neighbour of the centre vertex.
    const Vec2 twin{2.3 + 0.25 * default_snap_distance(domain), 2.0};
    std::vector<Vec2> positions = {centre, ring_point, twin};
    for (int k = 1; k < 6; ++k) {
        const double a = k * std::numbers::pi / 3.0;
        positions.push_back(centre + Vec2{0.3 * std::cos(a), 0.3 * std::sin(a)});
    }
    for (int k = 0; k < 12; ++k) {
        const double a = (k + 0.5) * std::numbers::pi / 6.0;
        positions.push_back(centre + Vec2{1.2 * std::cos(a), 1.2 * std::sin(a)});
    }
    std::vector<double> heights(positions.size(), 0.5);
    heights[0] = 1.5;  // a peak: removing it loses volume, which the ring makes up
    Tin tin = Tin::from_points(domain, positions, heights);
    const auto id_at = [&](Vec2 p) {
        for (VertexId v : test::live_ids(tin)) {
            if (tin.position(v) == p) return v;
        }
        ADD_FAILURE() << "no vertex at (" << p.x << ", " << p.y << ")";
        return VertexId{};
    };
    const VertexId peak = id_at(centre), a = id_at(ring_point), b = id_at(twin);
    ASSERT_TRUE(a.valid() && b.valid());
    std::vector<VertexId> ring;
    tin.neighbours(peak, ring);
    ASSERT_NE(std::find(ring.begin(), ring.end(), a), ring.end());
    ASSERT_EQ(std::find(ring.begin(), ring.end(), b), ring.end());

    const double v0 = tin.volume();
    EditReport report;
    ASSERT_TRUE(tin.remove_vertex(peak, VolumePolicy::Conserve, &report));
    ASSERT_NE(report.volume_change, 0.0);
    EXPECT_GT(tin.height(a), 0.5);  // the ring was raised
    EXPECT_EQ(tin.height(a), tin.height(b));
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveVertex, ReportPolicyReportsMeasuredChangeAndKeepsHeights) {
    Tin tin = Tin::random_points(Rect::from_size(5.0, 3.0), 600, 6, bumpy);
    auto ids = interior_ids(tin);
    std::mt19937_64 rng = test::test_rng(6);
    std::shuffle(ids.begin(), ids.end(), rng);
    ids.resize(400);
    bool any_nonzero = false;
    for (VertexId v : ids) {
        const TinSnapshot before_snap = tin.snapshot();
        const double before = tin.volume();
        EditReport report;
        ASSERT_TRUE(tin.remove_vertex(v, VolumePolicy::Report, &report));
        const double after = tin.volume();
        EXPECT_NEAR(report.volume_change, after - before, 1e-12 * std::abs(before));
        any_nonzero = any_nonzero || report.volume_change != 0.0;
        // Report leaves every surviving height alone.
        const VertexArrays& va = tin.vertices();
        for (std::size_t i = 0; i < va.size(); ++i) {
            if (va.alive[i]) {
                ASSERT_EQ(va.height[i], before_snap.vertices.height[i]) << i;
            }
        }
    }
    EXPECT_TRUE(any_nonzero);
    EXPECT_TRUE(close_rel(tin.volume(), brute_force_volume(tin), 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveVertex, PlanarRemovalKeepsThePlane) {
    // Removing vertices from a plane re-triangulates within the plane: nothing to compensate.
    const test::Plane plane{0.2, -0.7, 5.0};
    const Rect d = Rect::from_size(3.0, 3.0);
    Tin tin = Tin::random_points(d, 300, 7, plane);
    auto ids = interior_ids(tin);
    for (std::size_t i = 0; i < ids.size(); i += 2)
        ASSERT_TRUE(tin.remove_vertex(ids[i]));
    for (VertexId v : test::live_ids(tin)) {
        EXPECT_NEAR(tin.height(v), plane(tin.position(v)), 1e-12 * 8.0);
    }
    EXPECT_TRUE(close_rel(tin.volume(), plane.integral(d), 1e-12));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveVertex, RemovingEveryInteriorVertexLeavesTheRectangle) {
    Tin tin = Tin::random_points(Rect::from_size(2.0, 2.0), 200, 8, bumpy);
    const double v0 = tin.volume();
    for (VertexId v : interior_ids(tin))
        ASSERT_TRUE(tin.remove_vertex(v));
    EXPECT_EQ(tin.vertex_count(), 4u);
    EXPECT_EQ(tin.triangle_count(), 2u);
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * std::abs(v0));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(RemoveBorderVertex, MidSideVerticesGoAndTheRectangleStays) {
    // Vertices on every side of the domain, including two next to each other on one side, and
    // interior vertices: every non-corner border vertex goes, and with it the border gets
    // exactly the heights of the line between its remaining neighbours.
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 21, bumpy);
    const std::vector<Vec2> on_border = {
        {2.0, 0.0}, {2.5, 0.0}, {4.0, 1.5}, {1.0, 4.0}, {0.0, 3.0}};
    std::vector<double> hs;
    for (Vec2 p : on_border)
        hs.push_back(bumpy(p));
    const std::vector<VertexId> ids = tin.insert_points(on_border, hs);
    for (VertexId v : interior_ids(tin))
        EXPECT_FALSE(tin.remove_border_vertex(v)) << "interior";
    const TinSnapshot before = tin.snapshot();
    std::size_t corners = 0;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if ((p.x == 0.0 || p.x == 4.0) && (p.y == 0.0 || p.y == 4.0)) {
            EXPECT_FALSE(tin.remove_border_vertex(v)) << "corner";
            ++corners;
        }
    }
    EXPECT_EQ(corners, 4u);
    test::expect_snapshots_equal(before, tin.snapshot());
    for (VertexId v : ids) {
        const double v0 = tin.volume();
        EditReport report;
        ASSERT_TRUE(tin.remove_border_vertex(v, VolumePolicy::Report, &report));
        EXPECT_FALSE(tin.is_alive(v));
        EXPECT_EQ(report.vertices_removed, 1u);
        EXPECT_NEAR(tin.volume() - v0, report.volume_change, 1e-12);
        EXPECT_TRUE(test::tin_is_sound(tin));
    }
    // The domain is still the whole rectangle: every border point has a height, the linear
    // one between the corners now that no other vertex is on the border.
    LocateHint hint;
    for (double t = 0.0; t <= 1.0; t += 0.125) {
        const Vec2 p{4.0 * t, 0.0};
        ASSERT_TRUE(tin.height_at(p, &hint).has_value());
        EXPECT_NEAR(*tin.height_at(p, &hint), (1.0 - t) * bumpy({0, 0}) + t * bumpy({4, 0}), 1e-12);
    }
    EXPECT_NEAR(tin.volume(), test::brute_force_volume(tin), 1e-9);
}

TEST(RemoveBorderVertex, ConstrainedBorderVertexIsRefused) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 50, 22, bumpy);
    const VertexId edge = tin.insert_point({2.0, 0.0}, 1.0);
    const VertexId inside = tin.insert_point({2.0, 1.0}, 1.0);
    tin.insert_constraint(edge, inside, 1);
    const TinSnapshot before = tin.snapshot();
    EXPECT_FALSE(tin.remove_border_vertex(edge));
    test::expect_snapshots_equal(before, tin.snapshot());
    ASSERT_EQ(tin.release_constraints({}), 1u);
    EXPECT_TRUE(tin.remove_border_vertex(edge));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

}  // namespace
}  // namespace sandtin
