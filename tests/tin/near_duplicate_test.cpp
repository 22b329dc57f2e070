// Points a rounding error apart are one vertex (Tin::snap_distance): however a point arrives,
// by insertion, a constraint crossing or an edge split, no two vertices end up closer than the
// snap distance. Two such vertices at different heights are a vertical step the sand physics
// can never level (found: a groove stroked with erosion between stamps and r_S = 1 cm never
// came to rest, with vertices 1e-9 to 1e-16 m apart on its rims).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

/// The smallest distance between two live vertices (m), by comparing every pair: the scenes
/// here have a dozen vertices, and a pair split by a constrained edge has no edge between them,
/// so the shortest edge would miss it.
double closest_pair(const Tin& tin) {
    const std::vector<VertexId> ids = test::live_ids(tin);
    const VertexArrays& va = tin.vertices();
    double closest = 1e300;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        for (std::size_t j = i + 1; j < ids.size(); ++j)
            closest =
                std::min(closest, distance(va.position[ids[i].value], va.position[ids[j].value]));
    }
    return closest;
}

/// A unit square with a constrained segment c-d across its middle (y = 0.5).
struct Scene {
    Tin tin = Tin::from_points(Rect::from_size(1.0, 1.0),
                               std::vector<Vec2>{{0.3, 0.2}, {0.7, 0.8}, {0.4, 0.9}, {0.6, 0.1}},
                               std::vector<double>(4, 0.0));
    VertexId c = tin.insert_point({0.2, 0.5}, 0.1);
    VertexId d = tin.insert_point({0.8, 0.5}, 0.1);
    Scene() { tin.insert_constraint(c, d, 1); }
};

TEST(NearDuplicates, AConstraintFromAPointAHairOffAnotherSplitsItThere) {
    Scene s;
    // a lies a hair below c-d, so CGAL does not see it on the segment; a-b crosses c-d at a
    // distance of 1e-12 from a.
    const VertexId a = s.tin.insert_point({0.5, 0.5 - 1e-12}, 0.1);
    const VertexId b = s.tin.insert_point({0.5, 0.8}, 0.3);
    const std::size_t before = s.tin.vertex_count();
    s.tin.insert_constraint(a, b, 2);
    EXPECT_EQ(s.tin.vertex_count(), before);  // no vertex at the crossing
    EXPECT_GT(closest_pair(s.tin), s.tin.snap_distance());
    EXPECT_TRUE(s.tin.is_constrained_edge(s.c, a));
    EXPECT_TRUE(s.tin.is_constrained_edge(a, s.d));
    EXPECT_TRUE(s.tin.is_constrained_edge(a, b));
    EXPECT_TRUE(s.tin.check_valid().ok()) << s.tin.check_valid().summary();
}

TEST(NearDuplicates, APointAHairAcrossAnEdgeFromAVertexIsThatVertex) {
    Scene s;
    // q sits a hair above the constrained edge; p a hair below it, in a face that does not
    // have q as a corner (the constraint keeps c-d), yet 4e-10 m from q.
    const VertexId q = s.tin.insert_point({0.5, 0.5 + 2e-10}, 0.2);
    const std::size_t before = s.tin.vertex_count();
    const VertexId p = s.tin.insert_point_on_surface({0.5, 0.5 - 2e-10});
    EXPECT_EQ(p, q);
    EXPECT_EQ(s.tin.vertex_count(), before);
    EXPECT_EQ(s.tin.height(q), 0.2);  // the vertex keeps its own height
    EXPECT_GT(closest_pair(s.tin), s.tin.snap_distance());
    EXPECT_TRUE(s.tin.check_valid().ok()) << s.tin.check_valid().summary();
}

TEST(NearDuplicates, AnEdgeSplitBesideAVertexAtItsMiddleIsSkipped) {
    Scene s;
    s.tin.insert_point({0.5, 0.5 + 2e-10}, 0.2);
    const std::size_t before = s.tin.vertex_count();
    const EdgeSplit split{s.c, s.d, 0.5};
    const std::vector<VertexId> made =
        s.tin.split_edges(std::span<const EdgeSplit>(&split, 1), VolumePolicy::Conserve);
    ASSERT_EQ(made.size(), 1u);
    EXPECT_FALSE(made[0].valid());
    EXPECT_EQ(s.tin.vertex_count(), before);
    EXPECT_GT(closest_pair(s.tin), s.tin.snap_distance());
    // Away from that vertex the same edge still splits.
    const EdgeSplit elsewhere{s.c, s.d, 0.25};
    EXPECT_TRUE(
        s.tin.split_edges(std::span<const EdgeSplit>(&elsewhere, 1), VolumePolicy::Conserve)[0]
            .valid());
    EXPECT_TRUE(s.tin.check_valid().ok()) << s.tin.check_valid().summary();
}

}  // namespace
}  // namespace sandtin
