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

/// Whether a and b share an edge of the TIN.
bool joined(const Tin& tin, VertexId a, VertexId b) {
    std::vector<VertexId> ring;
    tin.neighbours(a, ring);
    return std::find(ring.begin(), ring.end(), b) != ring.end();
}

TEST(NearDuplicates, AnEdgeSplitBesideAVertexAtItsMiddleIsSkipped) {
    Scene s;
    // The bottom border edge between the domain's corners, with a vertex a hair inside it at
    // its middle: the apex of a sliver (a border edge is not constrained, so the point stays
    // beside it).
    const VertexId left = s.tin.insert_point_on_surface({0.0, 0.0});
    const VertexId right = s.tin.insert_point_on_surface({1.0, 0.0});
    s.tin.insert_point({0.5, 2e-10}, 0.2);
    ASSERT_TRUE(joined(s.tin, left, right));
    const std::size_t before = s.tin.vertex_count();
    const EdgeSplit split{left, right, 0.5};
    const std::vector<VertexId> made =
        s.tin.split_edges(std::span<const EdgeSplit>(&split, 1), VolumePolicy::Conserve);
    ASSERT_EQ(made.size(), 1u);
    EXPECT_FALSE(made[0].valid());
    EXPECT_EQ(s.tin.vertex_count(), before);
    EXPECT_GT(closest_pair(s.tin), s.tin.snap_distance());
    // Away from that vertex the same edge still splits.
    const EdgeSplit elsewhere{left, right, 0.25};
    EXPECT_TRUE(
        s.tin.split_edges(std::span<const EdgeSplit>(&elsewhere, 1), VolumePolicy::Conserve)[0]
            .valid());
    EXPECT_TRUE(s.tin.check_valid().ok()) << s.tin.check_valid().summary();
}

// A vertex a hair off a constrained edge is on it. Beside it, it would be the apex of a sliver
// that no Delaunay flip removes, and whose long edges no split can take apart (every split point
// folds the sliver over): under a relocation radius the sand could never reach it, and a groove
// eroded with r_S = 1 cm came to rest with edges up to 10^9 times steeper than repose.

TEST(NearDuplicates, APointAHairOffAConstrainedEdgeSplitsIt) {
    Scene s;
    const VertexId q = s.tin.insert_point({0.5, 0.5 + 3e-10}, 0.2);
    EXPECT_TRUE(s.tin.is_constrained_edge(s.c, q));
    EXPECT_TRUE(s.tin.is_constrained_edge(q, s.d));
    EXPECT_FALSE(joined(s.tin, s.c, s.d));
    EXPECT_EQ(s.tin.height(q), 0.2);
    EXPECT_TRUE(s.tin.check_valid().ok()) << s.tin.check_valid().summary();
}

TEST(NearDuplicates, AConstraintPassingAHairFromAVertexGoesThroughIt) {
    // As the groove left them: a midpoint a rounding error off the segment between two rim
    // points, then a later stamp's rim along the same segment. Here the offsets are explicit
    // (3e-10 and 5e-12 m, both sides), so the exact predicates see them off the line.
    Tin tin = Tin::from_points(Rect::from_size(1.0, 1.0),
                               std::vector<Vec2>{{0.3, 0.2}, {0.7, 0.8}, {0.4, 0.9}, {0.6, 0.1}},
                               std::vector<double>(4, 0.0));
    const VertexId a = tin.insert_point({0.2, 0.5}, 0.1);
    const VertexId b = tin.insert_point({0.8, 0.5}, 0.1);
    const VertexId m1 = tin.insert_point({0.35, 0.5 + 3e-10}, 0.3);
    const VertexId m2 = tin.insert_point({0.575, 0.5 - 5e-12}, -0.2);
    const VertexId off = tin.insert_point({0.5, 0.5 + 1e-4}, 0.0);  // well off: stays beside
    const std::size_t before = tin.vertex_count();
    const ConstraintId id = tin.insert_constraint(a, b, 1, VolumePolicy::Report);
    EXPECT_EQ(tin.vertex_count(), before);
    EXPECT_TRUE(tin.is_constrained_edge(a, m1));
    EXPECT_TRUE(tin.is_constrained_edge(m1, m2));
    EXPECT_TRUE(tin.is_constrained_edge(m2, b));
    EXPECT_FALSE(tin.is_on_constraint(off));
    const std::optional<ConstraintInfo> info = tin.constraint(id);
    ASSERT_TRUE(info.has_value());
    EXPECT_EQ(info->vertices, (std::vector<VertexId>{a, m1, m2, b}));
    // The vertices keep their heights (the volume is reported, not conserved, here).
    EXPECT_EQ(tin.height(m1), 0.3);
    EXPECT_EQ(tin.height(m2), -0.2);
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
    // Releasing the constraint and constraining the same segment again gives the same chain.
    tin.release_constraints(ReleaseFilter{});
    const ConstraintId again = tin.insert_constraint(a, b, 2);
    ASSERT_TRUE(tin.constraint(again).has_value());
    EXPECT_EQ(tin.constraint(again)->vertices, (std::vector<VertexId>{a, m1, m2, b}));
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

TEST(NearDuplicates, AConstraintAlongATinyTriangleEnds) {
    // Three vertices 1.0e-6 to 1.3e-6 m apart (found by `sandtin stress`): each lies within
    // the snap distance (1e-6 m) of the others' edge, and threading a constraint through the
    // third vertex by that distance alone went round the triangle for ever.
    Tin tin = Tin::from_points(Rect::from_size(1.0, 1.0),
                               std::vector<Vec2>{{0.3, 0.2}, {0.1, 0.4}, {0.4, 0.05}},
                               std::vector<double>(3, 0.0));
    const VertexId u = tin.insert_point({0.21461055552041883, 0.15125014311809551}, 0.0);
    const VertexId w = tin.insert_point({0.21461060592878406, 0.15124883690715382}, 0.0);
    const VertexId c = tin.insert_point({0.21461158000384309, 0.15124926019523552}, 0.0);
    ASSERT_EQ(tin.vertex_count(), 10u);  // the three corners, the domain's four, and u, w, c
    const ConstraintId id = tin.insert_constraint(u, w, 1);
    const std::optional<ConstraintInfo> info = tin.constraint(id);
    ASSERT_TRUE(info.has_value());
    EXPECT_EQ(info->vertices, (std::vector<VertexId>{u, w}));  // c is well off so short an edge
    EXPECT_FALSE(tin.is_on_constraint(c));
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
}

}  // namespace
}  // namespace sandtin
