// Tin::fence_bent_edges: after it, inserting the points and constraining the segments it was
// given leaves the surface as it was wherever the new vertices sit at the surface's own
// height. Oracles: the surface sampled on a grid before and after (it may only gain vertices,
// never change shape), a twin without the fence (which does change shape: the premise), and
// CGAL's own validity checks.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "geom/polygon_inclusion.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

/// An imported elevation model in miniature: 60 points over 100 m of hills, each triangle
/// metres wide and far from flat.
Tin hills() {
    return Tin::random_points(Rect::from_size(100.0, 100.0), 60, 7, [](Vec2 p) {
        return 20.0 + 8.0 * std::sin(p.x / 12.0) * std::cos(p.y / 9.0) + 0.05 * p.x;
    });
}

/// The largest change of the surface between `a` and `b` on a 201 x 201 grid over the domain.
double largest_change(const Tin& a, const Tin& b) {
    double worst = 0.0;
    LocateHint ha, hb;
    for (Vec2 p : test::grid_points(a.domain(), 201, 201))
        worst = std::max(worst, std::abs(*a.height_at(p, &ha) - *b.height_at(p, &hb)));
    return worst;
}

TEST(FenceBentEdges, PointsInsertedOnTheSurfaceThenChangeItNowhere) {
    const Tin original = hills();
    const std::vector<Vec2> points = {{41.3, 57.9}, {42.0, 58.4}, {70.2, 20.5}, {12.5, 88.0}};
    for (const bool fence : {false, true}) {
        SCOPED_TRACE(fence ? "fenced" : "unfenced");
        Tin tin = Tin::from_snapshot(original.snapshot());
        std::size_t fenced = 0;
        if (fence) fenced = tin.fence_bent_edges(points, {}, 1e-3, 1);
        for (Vec2 p : points)
            tin.insert_point(p, *tin.height_at(p));
        ASSERT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
        const double change = largest_change(original, tin);
        if (fence) {
            EXPECT_GT(fenced, 0u);
            EXPECT_LT(change, 1e-9);
            EXPECT_NEAR(tin.volume(), original.volume(), 1e-9 * original.volume());
        } else {
            // The premise: Delaunay insertion alone re-shapes these hills.
            EXPECT_GT(change, 0.05);
        }
    }
}

TEST(FenceBentEdges, SegmentsConstrainedAcrossTheHillsChangeItNowhere) {
    const Tin original = hills();
    // A closed square 6 m wide, sampled only at its corners: its sides cross several edges.
    const std::vector<Vec2> corners = {{47.0, 47.0}, {53.0, 47.0}, {53.0, 53.0}, {47.0, 53.0}};
    std::vector<std::array<Vec2, 2>> sides;
    for (std::size_t k = 0; k < corners.size(); ++k)
        sides.push_back({corners[k], corners[(k + 1) % corners.size()]});
    for (const bool fence : {false, true}) {
        SCOPED_TRACE(fence ? "fenced" : "unfenced");
        Tin tin = Tin::from_snapshot(original.snapshot());
        if (fence) {
            EXPECT_GT(tin.fence_bent_edges(corners, sides, 1e-3, 1), 0u);
        }
        std::vector<VertexId> ids;
        for (Vec2 p : corners)
            ids.push_back(tin.insert_point(p, *tin.height_at(p)));
        std::vector<std::array<VertexId, 2>> segments;
        for (std::size_t k = 0; k < ids.size(); ++k)
            segments.push_back({ids[k], ids[(k + 1) % ids.size()]});
        tin.insert_constraints(segments, 2, VolumePolicy::Report);
        ASSERT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
        const double change = largest_change(original, tin);
        if (fence) {
            EXPECT_LT(change, 1e-9);
        } else {
            EXPECT_GT(change, 0.05);
        }
    }
}

TEST(FenceBentEdges, LeavesFlatAndEnclosedEdgesFree) {
    const std::vector<Vec2> points = {{41.3, 57.9}, {70.2, 20.5}};
    // A plane bends nowhere.
    Tin plane = Tin::random_points(Rect::from_size(100.0, 100.0), 60, 7, test::Plane{0.1, -0.2, 3});
    EXPECT_EQ(plane.fence_bent_edges(points, {}, 1e-6, 1), 0u);
    EXPECT_EQ(plane.constraint_count(), 0u);
    Tin tin = hills();
    // A region holding every quadrilateral the points touch leaves them free too.
    const std::vector<Vec2> everything = {
        {-1.0, -1.0}, {101.0, -1.0}, {101.0, 101.0}, {-1.0, 101.0}};
    const PolygonInclusion within(everything, {50.0, 50.0});
    EXPECT_EQ(tin.fence_bent_edges(points, {}, 1e-3, 1, &within), 0u);
    // Points outside the domain are no error and fence nothing.
    const std::vector<Vec2> outside = {{-5.0, 50.0}, {50.0, 1e9}};
    EXPECT_EQ(tin.fence_bent_edges(outside, {}, 1e-3, 1), 0u);
    EXPECT_EQ(tin.constraint_count(), 0u);
    // What it fences carries the generation it was given.
    ASSERT_GT(tin.fence_bent_edges(points, {}, 1e-3, 5), 0u);
    for (const ConstraintInfo& c : tin.constraints())
        EXPECT_EQ(c.generation, 5u);
}

}  // namespace
}  // namespace sandtin
