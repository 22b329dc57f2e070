// Tin::vertices_in_region against a brute-force point-in-polygon over every vertex, and
// long-edge refinement against a brute-force scan of every triangle meeting the disc.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/refine.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {
namespace {

using test::distance_to_border;
using test::inside_polygon;
using test::live_ids;
using test::mesh_is_sound;

/// The λ of the shipped asset, four times larger, centred at (0.5, 0.5), edges of at most 1 cm.
std::vector<Vec2> big_lambda() {
    const std::vector<Vec2> cm = {{4.5, -5.0},  {2.5, -5.0}, {0.0, 0.2},  {-2.6, -5.0},
                                  {-4.6, -5.0}, {-1.0, 1.5}, {-2.8, 5.0}, {-0.8, 5.0}};
    std::vector<Vec2> corners;
    for (Vec2 p : cm)
        corners.push_back(Vec2{0.5, 0.5} + p * 0.04);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
        const int n = static_cast<int>(std::ceil(distance(a, b) / 0.01));
        for (int k = 0; k < n; ++k)
            out.push_back(lerp(a, b, static_cast<double>(k) / n));
    }
    return out;
}

void check_region(Tin& tin, const std::vector<Vec2>& contour) {
    // Constrain the contour at the surface heights.
    std::vector<double> hs;
    for (Vec2 p : contour)
        hs.push_back(*tin.height_at(p));
    const std::vector<VertexId> ids = tin.insert_points(contour, hs);
    tin.insert_constraint(ids, /*closed=*/true, 1);
    ASSERT_TRUE(mesh_is_sound(tin));
    // Seeds: a few points well inside, found by the test itself.
    std::vector<Vec2> seeds;
    for (Vec2 p : test::random_points_in(test::kUnitSquare, 5000, 17)) {
        if (test::inside_by(p, contour, 0.005)) seeds.push_back(p);
        if (seeds.size() == 3) break;
    }
    ASSERT_EQ(seeds.size(), 3u);
    const std::vector<VertexId> found = tin.vertices_in_region(seeds, contour);
    const std::set<VertexId> got(found.begin(), found.end());
    EXPECT_EQ(got.size(), found.size()) << "a vertex was reported twice";
    std::set<VertexId> expected;
    for (VertexId v : live_ids(tin)) {
        const Vec2 p = tin.position(v);
        if (inside_polygon(p, contour) || distance_to_border(p, contour) <= 1e-12)
            expected.insert(v);
    }
    EXPECT_GT(expected.size(), contour.size());
    for (VertexId v : expected)
        EXPECT_TRUE(got.count(v)) << "missed " << tin.position(v).x << ", " << tin.position(v).y;
    for (VertexId v : got)
        EXPECT_TRUE(expected.count(v))
            << "outside " << tin.position(v).x << ", " << tin.position(v).y;
    for (VertexId v : ids)
        EXPECT_TRUE(got.count(v)) << "contour vertex missing";
}

TEST(Region, VerticesInRegionOfAConstrainedNonConvexContour) {
    Tin tin = Tin::random_points(test::kUnitSquare, 5000, 501, test::rolling_sand);
    check_region(tin, big_lambda());
}

TEST(Region, VerticesInRegionOfAConstrainedCircle) {
    Tin tin = Tin::random_points(test::kUnitSquare, 3000, 502, test::rolling_sand);
    std::vector<Vec2> circle;
    for (Vec2 p : circle_contour(0.2, 64))
        circle.push_back(p + Vec2{0.45, 0.55});
    check_region(tin, circle);
}

// ---- 16. Long-edge refinement --------------------------------------------------------------

bool triangle_meets_disc(Vec2 a, Vec2 b, Vec2 c, Vec2 centre, double r) {
    const auto w = test::barycentric(centre, a, b, c);
    if (w[0] >= 0.0L && w[1] >= 0.0L && w[2] >= 0.0L) return true;
    return test::distance_to_segment_ld(centre, a, b) <= r ||
           test::distance_to_segment_ld(centre, b, c) <= r ||
           test::distance_to_segment_ld(centre, c, a) <= r;
}

double longest_edge_near(const Tin& tin, Vec2 centre, double r) {
    double longest = 0.0;
    for (const auto& t : tin.triangles()) {
        const Vec2 a = tin.position(t[0]), b = tin.position(t[1]), c = tin.position(t[2]);
        if (!triangle_meets_disc(a, b, c, centre, r)) continue;
        longest = std::max({longest, distance(a, b), distance(b, c), distance(c, a)});
    }
    return longest;
}

TEST(Refine, NoLongEdgeLeftNearThePointAndVolumeConserved) {
    for (const std::size_t points : {0u, 30u, 300u}) {
        SCOPED_TRACE(std::to_string(points) + " points");
        Tin tin = points == 0
                      ? Tin::flat_rectangle(test::kUnitSquare, 0.1)
                      : Tin::random_points(test::kUnitSquare, points, 511, test::rolling_sand);
        const Vec2 c{0.45, 0.6};
        const double r = 0.15, max_length = 0.04;
        ASSERT_GT(longest_edge_near(tin, c, r), max_length);
        const std::size_t n = tin.vertex_count();
        const double v0 = tin.volume();
        EditReport report;
        const std::size_t inserted =
            refine_long_edges(tin, c, r, max_length, nullptr, 200000, &report).inserted;
        EXPECT_EQ(tin.vertex_count(), n + inserted);
        EXPECT_EQ(report.vertices_created, inserted);
        EXPECT_LE(longest_edge_near(tin, c, r), max_length * (1.0 + 1e-12));
        EXPECT_NEAR(tin.volume(), v0, 1e-12 * v0);
        EXPECT_NEAR(test::brute_force_volume(tin), v0, 1e-12 * v0);
        EXPECT_TRUE(mesh_is_sound(tin));
        // Far from the disc nothing was refined: an edge longer than the limit survives there
        // (when the terrain had one to begin with).
        if (points == 30) {
            EXPECT_GT(longest_edge_near(tin, {0.05, 0.05}, 0.01), max_length);
        }
    }
}

TEST(Refine, StopsAtTheInsertionLimit) {
    Tin tin = Tin::flat_rectangle(test::kUnitSquare, 0.1);
    const std::size_t inserted =
        refine_long_edges(tin, {0.5, 0.5}, 0.3, 0.01, nullptr, 10).inserted;
    EXPECT_GT(inserted, 0u);
    EXPECT_LE(inserted, 10u);
    EXPECT_EQ(tin.vertex_count(), 4u + inserted);
    EXPECT_TRUE(mesh_is_sound(tin));
    // Degenerate arguments do nothing.
    EXPECT_EQ(refine_long_edges(tin, {0.5, 0.5}, 0.3, 0.0).inserted, 0u);
    EXPECT_EQ(refine_long_edges(tin, {0.5, 0.5}, 0.0, 0.01).inserted, 0u);
}

}  // namespace
}  // namespace sandtin
