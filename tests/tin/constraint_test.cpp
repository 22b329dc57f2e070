// Constraints: segments, polylines, crossings, re-insertion, release.
// Oracles: crossing points and their heights re-derived from the segment endpoints
// (intersection + linear interpolation along the old constraint), constrained-edge counts from
// the geometry, slot masks checked against the triangles, volume before/after, Delaunay
// property of the released edges checked without CGAL.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::close_rel;

double rolling(Vec2 p) {
    return 2.0 + 0.5 * std::sin(0.9 * p.x) * std::cos(0.7 * p.y) + 0.03 * p.x;
}

Tin make_terrain(std::uint64_t seed = 1, std::size_t points = 200) {
    return Tin::random_points(Rect::from_size(10.0, 10.0), points, seed, rolling);
}

std::set<VertexId> live_set(const Tin& tin) {
    const auto ids = test::live_ids(tin);
    return {ids.begin(), ids.end()};
}

std::vector<VertexId> new_vertices(const std::set<VertexId>& before, const Tin& tin) {
    std::vector<VertexId> out;
    for (VertexId v : test::live_ids(tin)) {
        if (!before.count(v)) out.push_back(v);
    }
    return out;
}

/// Constrained edges counted from the slot masks: each interior constrained edge appears in
/// two triangles, each border one in one.
std::set<std::pair<VertexId, VertexId>> constrained_edges_from_masks(const Tin& tin) {
    std::set<std::pair<VertexId, VertexId>> edges;
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        const auto t = tin.slot_triangle(s);
        if (!t[0].valid()) {
            EXPECT_EQ(tin.slot_constraint_mask(s), 0)
                << "free slot " << s << " has constraint bits";
            continue;
        }
        for (int i = 0; i < 3; ++i) {
            if (!(tin.slot_constraint_mask(s) & (1u << i))) continue;
            VertexId a = t[static_cast<std::size_t>((i + 1) % 3)];
            VertexId b = t[static_cast<std::size_t>((i + 2) % 3)];
            if (b < a) std::swap(a, b);
            edges.insert({a, b});
        }
    }
    return edges;
}

void expect_constrained_edges(const Tin& tin,
                              const std::set<std::pair<VertexId, VertexId>>& expected) {
    EXPECT_EQ(tin.constrained_edge_count(), expected.size());
    EXPECT_EQ(constrained_edges_from_masks(tin), expected);
    for (const auto& [a, b] : expected) {
        EXPECT_TRUE(tin.is_constrained_edge(a, b)) << a.value << "-" << b.value;
        EXPECT_TRUE(tin.is_constrained_edge(b, a)) << b.value << "-" << a.value;
    }
}

std::pair<VertexId, VertexId> edge(VertexId a, VertexId b) {
    return a < b ? std::pair{a, b} : std::pair{b, a};
}

/// The consecutive pairs of a constraint's vertex list.
std::set<std::pair<VertexId, VertexId>> polyline_edges(const std::vector<VertexId>& vs,
                                                       bool closed) {
    std::set<std::pair<VertexId, VertexId>> out;
    for (std::size_t i = 0; i + 1 < vs.size(); ++i)
        out.insert(edge(vs[i], vs[i + 1]));
    if (closed && vs.size() > 2 && vs.front() != vs.back()) out.insert(edge(vs.back(), vs.front()));
    return out;
}

TEST(Constraints, SegmentBecomesAConstrainedEdge) {
    Tin tin = make_terrain();
    const VertexId a = tin.insert_point({2.0, 2.0}, 1.0);
    const VertexId b = tin.insert_point({7.0, 3.5}, 3.0);
    EXPECT_FALSE(tin.is_constrained_edge(a, b));
    EXPECT_FALSE(tin.newest_constraint_generation().has_value());
    const double v0 = tin.volume();
    const std::size_t n = tin.vertex_count();
    const ConstraintId id = tin.insert_constraint(a, b, 5);
    ASSERT_TRUE(id.valid());
    EXPECT_EQ(tin.newest_constraint_generation(), std::optional<Generation>(5));
    EXPECT_EQ(tin.vertex_count(), n);
    expect_constrained_edges(tin, {edge(a, b)});
    EXPECT_TRUE(tin.is_on_constraint(a));
    EXPECT_TRUE(tin.is_on_constraint(b));
    EXPECT_EQ(tin.constraint_count(), 1u);
    const auto all = tin.constraints();
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0].id, id);
    EXPECT_EQ(all[0].generation, 5u);
    EXPECT_EQ(all[0].vertices, (std::vector<VertexId>{a, b}));
    const auto one = tin.constraint(id);
    ASSERT_TRUE(one.has_value());
    EXPECT_EQ(one->vertices, all[0].vertices);
    EXPECT_FALSE(tin.constraint(ConstraintId{id.value + 1}).has_value());
    EXPECT_FALSE(tin.constraint(ConstraintId{}).has_value());
    // Conserve is the default.
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, ReportPolicyReportsMeasuredVolumeChange) {
    Tin tin = make_terrain(2, 400);
    std::mt19937_64 rng = test::test_rng(2);
    std::uniform_real_distribution<double> u(0.5, 9.5);
    bool any_nonzero = false;
    for (int i = 0; i < 30; ++i) {
        const Vec2 p{u(rng), u(rng)};
        const Vec2 q = p + Vec2{std::cos(i * 0.7), std::sin(i * 0.7)} * 0.8;
        if (!tin.domain().contains(q)) continue;
        const VertexId a = tin.insert_point_on_surface(p);
        const VertexId b = tin.insert_point_on_surface(q);
        const double before = tin.volume();
        EditReport report;
        tin.insert_constraint(a, b, 1, VolumePolicy::Report, &report);
        EXPECT_NEAR(report.volume_change, tin.volume() - before, 1e-12 * before);
        any_nonzero = any_nonzero || report.volume_change != 0.0;
    }
    EXPECT_TRUE(any_nonzero) << "constraints through a curved surface should flip some edges";
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, SegmentThroughExistingVerticesIsSplitAtThem) {
    // Integer grid: the diagonal from (1,1) to (5,5) passes exactly through three vertices.
    Tin tin = Tin::regular_grid(Rect::from_size(8.0, 8.0), 8, 8, rolling);
    auto at = [&](double x, double y) {
        const auto loc = tin.locate({x, y});
        EXPECT_EQ(loc.kind, Location::Kind::OnVertex);
        for (VertexId v : loc.corners) {
            if (tin.position(v) == Vec2{x, y}) return v;
        }
        ADD_FAILURE() << "no vertex at " << x << "," << y;
        return VertexId{};
    };
    const std::vector<VertexId> diag = {at(1, 1), at(2, 2), at(3, 3), at(4, 4), at(5, 5)};
    const std::size_t n = tin.vertex_count();
    EditReport report;
    const ConstraintId id =
        tin.insert_constraint(diag.front(), diag.back(), 1, VolumePolicy::Report, &report);
    EXPECT_EQ(report.vertices_created, 0u);
    EXPECT_EQ(tin.vertex_count(), n);
    expect_constrained_edges(tin, polyline_edges(diag, false));
    ASSERT_TRUE(tin.constraint(id).has_value());
    EXPECT_EQ(tin.constraint(id)->vertices, diag);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

struct Crossing {
    Vec2 point;
    double height;
};

/// Height of the piecewise-linear profile through (positions, heights) at q, which lies on it.
double profile_height(const std::vector<Vec2>& ps, const std::vector<double>& hs, Vec2 q) {
    for (std::size_t i = 0; i + 1 < ps.size(); ++i) {
        const Vec2 a = ps[i];
        const Vec2 b = ps[i + 1];
        if (test::distance_to_segment_ld(q, a, b) > 1e-9) continue;
        const double t = distance(a, q) / distance(a, b);
        return hs[i] + t * (hs[i + 1] - hs[i]);
    }
    ADD_FAILURE() << "point not on the profile";
    return std::nan("");
}

TEST(Constraints, CrossingCreatesVertexAtHeightOfOldConstraint) {
    Tin tin = make_terrain(3);
    const Vec2 pa{2.0, 2.0}, pb{8.0, 6.0}, pc{3.0, 7.0}, pd{7.0, 1.0};
    const VertexId a = tin.insert_point(pa, 1.0);
    const VertexId b = tin.insert_point(pb, 4.0);
    const VertexId c = tin.insert_point(pc, 0.0);
    const VertexId d = tin.insert_point(pd, 10.0);
    const ConstraintId ab = tin.insert_constraint(a, b, 1, VolumePolicy::Report);
    const auto before = live_set(tin);
    EditReport report;
    const ConstraintId cd = tin.insert_constraint(c, d, 2, VolumePolicy::Report, &report);
    EXPECT_NE(ab, cd);
    const auto created = new_vertices(before, tin);
    ASSERT_EQ(created.size(), 1u);
    EXPECT_EQ(report.vertices_created, 1u);
    const VertexId x = created[0];
    const auto [expected_point, t] = test::segment_intersection(pa, pb, pc, pd);
    EXPECT_NEAR(tin.position(x).x, expected_point.x, 1e-9);
    EXPECT_NEAR(tin.position(x).y, expected_point.y, 1e-9);
    EXPECT_NEAR(tin.position(x).x, 5.0, 1e-9);  // worked by hand: the lines meet at (5, 4)
    EXPECT_NEAR(tin.position(x).y, 4.0, 1e-9);
    // Height of the OLD constraint a-b at that point (a and b keep their heights: Report).
    EXPECT_EQ(tin.height(a), 1.0);
    EXPECT_EQ(tin.height(b), 4.0);
    EXPECT_NEAR(tin.height(x), 1.0 + t * (4.0 - 1.0), 1e-9);
    EXPECT_NEAR(tin.height(x), 2.5, 1e-9);
    // Both constraints now pass through x.
    EXPECT_EQ(tin.constraint(ab)->vertices, (std::vector<VertexId>{a, x, b}));
    EXPECT_EQ(tin.constraint(cd)->vertices, (std::vector<VertexId>{c, x, d}));
    EXPECT_FALSE(tin.is_constrained_edge(a, b));
    expect_constrained_edges(tin, {edge(a, x), edge(x, b), edge(c, x), edge(x, d)});
    EXPECT_TRUE(tin.is_on_constraint(x));
    EXPECT_FALSE(tin.remove_vertex(x));
    EXPECT_TRUE(test::tin_is_sound(tin));

    // A third constraint crosses a-x (part of a-b) and x-d (part of c-d, whose profile now
    // bends at x).
    const Vec2 pe{1.0, 3.0}, pf{9.0, 3.0};
    const VertexId e = tin.insert_point(pe, -1.0);
    const VertexId f = tin.insert_point(pf, 6.0);
    const auto before2 = live_set(tin);
    const ConstraintId ef = tin.insert_constraint(e, f, 3, VolumePolicy::Report);
    const auto created2 = new_vertices(before2, tin);
    ASSERT_EQ(created2.size(), 2u);
    const Crossing on_ab{test::segment_intersection(pa, pb, pe, pf).first, 0.0};
    const Crossing on_cd{test::segment_intersection(pc, pd, pe, pf).first, 0.0};
    const double h_ab = profile_height({pa, pb}, {1.0, 4.0}, on_ab.point);
    const double h_cd = profile_height({pc, expected_point, pd}, {0.0, 2.5, 10.0}, on_cd.point);
    EXPECT_NEAR(h_ab, 1.75, 1e-12);  // by hand: a quarter of the way from a to b
    EXPECT_NEAR(h_cd, 5.0, 1e-9);    // by hand: a third of the way from x to d
    int matched = 0;
    for (VertexId v : created2) {
        const Vec2 p = tin.position(v);
        if (distance(p, on_ab.point) < 1e-9) {
            EXPECT_NEAR(tin.height(v), h_ab, 1e-9);
            ++matched;
        } else if (distance(p, on_cd.point) < 1e-9) {
            EXPECT_NEAR(tin.height(v), h_cd, 1e-9);
            ++matched;
        } else {
            ADD_FAILURE() << "unexpected new vertex at " << p.x << "," << p.y;
        }
    }
    EXPECT_EQ(matched, 2);
    EXPECT_EQ(tin.constraint(ef)->vertices.size(), 4u);
    EXPECT_EQ(tin.constraint_count(), 3u);
    EXPECT_EQ(tin.constrained_edge_count(), 4u + 2u + 3u);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, LongConstraintCrossingManyOldOnes) {
    for (VolumePolicy policy : {VolumePolicy::Report, VolumePolicy::Conserve}) {
        SCOPED_TRACE(policy == VolumePolicy::Report ? "Report" : "Conserve");
        Tin tin = make_terrain(4, 300);
        std::vector<std::pair<Vec2, Vec2>> old_segments;
        std::vector<std::pair<double, double>> old_heights;
        for (int i = 1; i <= 9; ++i) {
            const Vec2 p{i + 0.05 * i, 1.0 + 0.1 * i};
            const Vec2 q{i - 0.03 * i, 9.0 - 0.05 * i};
            const double hp = 0.5 * i;
            const double hq = 7.0 - 0.3 * i;
            const VertexId vp = tin.insert_point(p, hp);
            const VertexId vq = tin.insert_point(q, hq);
            tin.insert_constraint(vp, vq, static_cast<Generation>(i), VolumePolicy::Report);
            old_segments.push_back({p, q});
            old_heights.push_back({hp, hq});
        }
        const Vec2 s{0.3, 5.3};
        const Vec2 e{9.8, 4.1};
        const VertexId vs = tin.insert_point(s, 1.0);
        const VertexId ve = tin.insert_point(e, 1.0);
        const auto before = live_set(tin);
        const double volume_before = tin.volume();
        EditReport report;
        const ConstraintId id = tin.insert_constraint(vs, ve, 100, policy, &report);
        const auto created = new_vertices(before, tin);
        ASSERT_EQ(created.size(), 9u);
        EXPECT_EQ(report.vertices_created, 9u);
        EXPECT_EQ(tin.constraint(id)->vertices.size(), 11u);
        if (policy == VolumePolicy::Conserve) {
            EXPECT_LE(std::abs(tin.volume() - volume_before), 1e-12 * volume_before);
        } else {
            EXPECT_NEAR(report.volume_change, tin.volume() - volume_before, 1e-12 * volume_before);
            for (std::size_t k = 0; k < old_segments.size(); ++k) {
                const auto [p, t] =
                    test::segment_intersection(old_segments[k].first, old_segments[k].second, s, e);
                const double h =
                    old_heights[k].first + t * (old_heights[k].second - old_heights[k].first);
                bool found = false;
                for (VertexId v : created) {
                    if (distance(tin.position(v), p) < 1e-9) {
                        found = true;
                        EXPECT_NEAR(tin.height(v), h, 1e-9) << "crossing " << k;
                    }
                }
                EXPECT_TRUE(found) << "no vertex at crossing " << k;
            }
        }
        EXPECT_EQ(tin.constrained_edge_count(), 9u * 2u + 10u);
        EXPECT_TRUE(test::tin_is_sound(tin));
    }
}

TEST(Constraints, ReinsertingReturnsSameIdWithMaxGeneration) {
    Tin tin = make_terrain(5);
    const VertexId a = tin.insert_point({3.0, 3.0}, 1.0);
    const VertexId b = tin.insert_point({6.0, 4.0}, 1.0);
    const ConstraintId id = tin.insert_constraint(a, b, 5);
    const ConstraintId again = tin.insert_constraint(a, b, 3);
    EXPECT_EQ(again, id);
    ASSERT_TRUE(tin.constraint(id).has_value());
    EXPECT_EQ(tin.constraint(id)->generation, 5u) << "an older generation must not lower it";
    const ConstraintId newer = tin.insert_constraint(a, b, 9);
    EXPECT_EQ(newer, id);
    EXPECT_EQ(tin.constraint(id)->generation, 9u);
    EXPECT_EQ(tin.constraint_count(), 1u);
    EXPECT_EQ(tin.constrained_edge_count(), 1u);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, ReinsertingReversedSegmentReturnsSameId) {
    Tin tin = make_terrain(5);
    const VertexId a = tin.insert_point({3.0, 3.0}, 1.0);
    const VertexId b = tin.insert_point({6.0, 4.0}, 1.0);
    const ConstraintId id = tin.insert_constraint(a, b, 5);
    EXPECT_EQ(tin.insert_constraint(b, a, 7), id);
    EXPECT_EQ(tin.constraint_count(), 1u);
    ASSERT_TRUE(tin.constraint(id).has_value());
    EXPECT_EQ(tin.constraint(id)->generation, 7u);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, ClosedAndOpenPolylines) {
    Tin tin = make_terrain(6);
    std::vector<VertexId> ring;
    for (int i = 0; i < 7; ++i) {
        const double ang = 2.0 * std::numbers::pi * i / 7.0;
        ring.push_back(
            tin.insert_point_on_surface(Vec2{5.0, 5.0} + Vec2{std::cos(ang), std::sin(ang)} * 1.5));
    }
    const double v0 = tin.volume();
    const ConstraintId closed = tin.insert_constraint(ring, true, 2);
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    std::set<std::pair<VertexId, VertexId>> expected;
    for (std::size_t i = 0; i < ring.size(); ++i)
        expected.insert(edge(ring[i], ring[(i + 1) % ring.size()]));
    expect_constrained_edges(tin, expected);
    const auto info = tin.constraint(closed);
    ASSERT_TRUE(info.has_value());
    EXPECT_EQ(info->generation, 2u);
    EXPECT_EQ(info->vertices.front(), ring.front());
    EXPECT_EQ(polyline_edges(info->vertices, true), expected);

    std::vector<VertexId> path;
    for (int i = 0; i < 4; ++i)
        path.push_back(tin.insert_point_on_surface({1.0 + 0.9 * i, 8.5 + 0.3 * (i % 2)}));
    const ConstraintId open = tin.insert_constraint(path, false, 3);
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        expected.insert(edge(path[i], path[i + 1]));
    expect_constrained_edges(tin, expected);
    EXPECT_FALSE(tin.is_constrained_edge(path.front(), path.back()));
    EXPECT_EQ(tin.constraint(open)->vertices, path);
    EXPECT_EQ(tin.constraint_count(), 2u);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

TEST(Constraints, RejectsBadPolylinesWithoutChangingAnything) {
    Tin tin = make_terrain(7);
    const VertexId a = tin.insert_point({3.0, 3.0}, 1.0);
    const VertexId b = tin.insert_point({6.0, 4.0}, 1.0);
    const VertexId dead = tin.insert_point({5.0, 8.0}, 1.0);
    ASSERT_TRUE(tin.remove_vertex(dead));
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    const std::vector<VertexId> single = {a};
    const std::vector<VertexId> repeated = {a, a, b};
    const std::vector<VertexId> with_dead = {a, b, dead};
    EXPECT_THROW(tin.insert_constraint(single, false, 1), std::invalid_argument);
    EXPECT_THROW(tin.insert_constraint(repeated, false, 1), std::invalid_argument);
    EXPECT_THROW(tin.insert_constraint(with_dead, false, 1), std::invalid_argument);
    EXPECT_THROW(tin.insert_constraint(a, a, 1), std::invalid_argument);
    EXPECT_THROW(tin.insert_constraint(a, dead, 1), std::invalid_argument);
    EXPECT_THROW(tin.insert_constraint(a, VertexId{}, 1), std::invalid_argument);
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(Constraints, PointInsertedOnAConstrainedEdgeSplitsIt) {
    Tin tin = make_terrain(8);
    const VertexId a = tin.insert_point({2.0, 5.0}, 1.0);
    const VertexId b = tin.insert_point({8.0, 5.0}, 4.0);
    // Report: a and b keep their heights (Conserve could shift them to compensate flips).
    const ConstraintId id = tin.insert_constraint(a, b, 1, VolumePolicy::Report);
    ASSERT_EQ(tin.height(a), 1.0);
    ASSERT_EQ(tin.height(b), 4.0);
    const VertexId m = tin.insert_point_on_surface({4.0, 5.0}, nullptr, VolumePolicy::Report);
    EXPECT_NEAR(tin.height(m), 1.0 + (4.0 - 1.0) / 3.0, 1e-12);  // a third of the way along a-b
    EXPECT_EQ(tin.constraint(id)->vertices, (std::vector<VertexId>{a, m, b}));
    expect_constrained_edges(tin, {edge(a, m), edge(m, b)});
    EXPECT_TRUE(tin.is_on_constraint(m));
    EXPECT_FALSE(tin.remove_vertex(m));
    EXPECT_TRUE(test::tin_is_sound(tin));
}

class ReleaseTest : public ::testing::Test {
  protected:
    void SetUp() override {
        // Short, disjoint constraints: three generations in region A (x < 5), three in B.
        for (int g = 1; g <= 3; ++g) {
            for (int region = 0; region < 2; ++region) {
                const double x0 = region == 0 ? 1.0 : 6.0;
                const double y = 1.0 + 2.0 * g + 0.1 * region;
                const VertexId p = tin.insert_point_on_surface({x0, y});
                const VertexId q = tin.insert_point_on_surface({x0 + 2.5, y + 0.4});
                const ConstraintId id = tin.insert_constraint(p, q, static_cast<Generation>(g));
                entries.push_back({id, static_cast<Generation>(g), region, p, q});
            }
        }
        ASSERT_EQ(tin.constraint_count(), 6u);
    }

    struct Entry {
        ConstraintId id;
        Generation generation;
        int region;
        VertexId p, q;
    };

    /// Checks that exactly the entries not in `released` remain, via every query.
    void expect_remaining(const std::set<std::size_t>& released) {
        std::set<std::pair<VertexId, VertexId>> expected_edges;
        std::set<std::uint32_t> expected_ids;
        for (std::size_t k = 0; k < entries.size(); ++k) {
            const Entry& e = entries[k];
            const bool alive = !released.count(k);
            EXPECT_EQ(tin.constraint(e.id).has_value(), alive) << "entry " << k;
            EXPECT_EQ(tin.is_constrained_edge(e.p, e.q), alive) << "entry " << k;
            if (alive) {
                expected_edges.insert(edge(e.p, e.q));
                expected_ids.insert(e.id.value);
                EXPECT_EQ(tin.constraint(e.id)->generation, e.generation);
            }
        }
        std::set<std::uint32_t> ids;
        for (const ConstraintInfo& c : tin.constraints())
            ids.insert(c.id.value);
        EXPECT_EQ(ids, expected_ids);
        EXPECT_EQ(tin.constraint_count(), expected_ids.size());
        expect_constrained_edges(tin, expected_edges);
        EXPECT_TRUE(test::tin_is_sound(tin));
    }

    Tin tin = make_terrain(9, 300);
    std::vector<Entry> entries;
    const std::vector<Vec2> region_a = {{0.0, 0.0}, {5.0, 0.0}, {5.0, 10.0}, {0.0, 10.0}};
    const std::vector<Vec2> region_b = {{5.5, 0.0}, {10.0, 0.0}, {10.0, 10.0}, {5.5, 10.0}};
};

TEST_F(ReleaseTest, ByGeneration) {
    ReleaseFilter f;
    f.generation = 2;
    const double v0 = tin.volume();
    EXPECT_EQ(tin.release_constraints(f), 2u);
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    expect_remaining({2, 3});
}

TEST_F(ReleaseTest, OlderThan) {
    ReleaseFilter f;
    f.older_than = 3;
    EXPECT_EQ(tin.release_constraints(f), 4u);
    expect_remaining({0, 1, 2, 3});
    f.older_than = 1;
    EXPECT_EQ(tin.release_constraints(f), 0u);
}

TEST_F(ReleaseTest, TouchingPolygon) {
    ReleaseFilter f;
    f.touching_polygon = region_b;
    EXPECT_EQ(tin.release_constraints(f), 3u);
    expect_remaining({1, 3, 5});
}

TEST_F(ReleaseTest, PolygonCrossingASegmentWithoutContainingItsEndpoints) {
    // A thin vertical strip through the middle of region A's segments (x from 2.0 to 2.2).
    const std::vector<Vec2> strip = {{2.0, 0.5}, {2.2, 0.5}, {2.2, 9.5}, {2.0, 9.5}};
    ReleaseFilter f;
    f.touching_polygon = strip;
    EXPECT_EQ(tin.release_constraints(f), 3u);
    expect_remaining({0, 2, 4});
}

TEST_F(ReleaseTest, PolygonContainingOnlyOneEndpoint) {
    // Small boxes around the first, then the last, vertex of single segments.
    const Vec2 first = tin.position(entries[0].p);
    const std::vector<Vec2> box_first = {first + Vec2{-0.2, -0.2}, first + Vec2{0.2, -0.2},
                                         first + Vec2{0.2, 0.2}, first + Vec2{-0.2, 0.2}};
    ReleaseFilter f;
    f.touching_polygon = box_first;
    EXPECT_EQ(tin.release_constraints(f), 1u) << "box around the first vertex of entry 0";
    const Vec2 last = tin.position(entries[3].q);
    const std::vector<Vec2> box_last = {last + Vec2{-0.2, -0.2}, last + Vec2{0.2, -0.2},
                                        last + Vec2{0.2, 0.2}, last + Vec2{-0.2, 0.2}};
    ReleaseFilter g;
    g.touching_polygon = box_last;
    EXPECT_EQ(tin.release_constraints(g), 1u) << "box around the last vertex of entry 3";
    expect_remaining({0, 3});
}

TEST_F(ReleaseTest, CombinedConditionsMustAllHold) {
    ReleaseFilter f;
    f.older_than = 3;
    f.touching_polygon = region_a;
    EXPECT_EQ(tin.release_constraints(f), 2u);  // generations 1 and 2 in A
    expect_remaining({0, 2});
    ReleaseFilter g;
    g.generation = 3;
    g.touching_polygon = region_b;
    EXPECT_EQ(tin.release_constraints(g), 1u);
    expect_remaining({0, 2, 5});
    ReleaseFilter h;
    h.generation = 1;
    h.older_than = 1;  // contradictory: nothing matches
    EXPECT_EQ(tin.release_constraints(h), 0u);
    expect_remaining({0, 2, 5});
}

TEST_F(ReleaseTest, NothingMatchingChangesNothing) {
    tin.take_changes();
    const TinSnapshot before = tin.snapshot();
    ReleaseFilter f;
    f.generation = 77;
    EXPECT_EQ(tin.release_constraints(f), 0u);
    const std::vector<Vec2> far = {{4.9, 0.0}, {5.4, 0.0}, {5.4, 0.5}, {4.9, 0.5}};
    ReleaseFilter g;
    g.touching_polygon = far;
    EXPECT_EQ(tin.release_constraints(g), 0u);
    test::expect_snapshots_equal(before, tin.snapshot());
    EXPECT_TRUE(tin.take_changes().empty());
    expect_remaining({});
}

TEST_F(ReleaseTest, EmptyFilterReleasesEverything) {
    EXPECT_EQ(tin.release_constraints({}), 6u);
    expect_remaining({0, 1, 2, 3, 4, 5});
}

TEST_F(ReleaseTest, ReleaseById) {
    EXPECT_TRUE(tin.release_constraint(entries[4].id));
    EXPECT_FALSE(tin.release_constraint(entries[4].id));
    EXPECT_FALSE(tin.release_constraint(ConstraintId{}));
    EXPECT_FALSE(tin.release_constraint(ConstraintId{1000}));
    expect_remaining({4});
}

TEST_F(ReleaseTest, ReportPolicyReportsMeasuredChange) {
    const double before = tin.volume();
    EditReport report;
    EXPECT_EQ(tin.release_constraints({}, VolumePolicy::Report, &report), 6u);
    EXPECT_NEAR(report.volume_change, tin.volume() - before, 1e-12 * before);
    expect_remaining({0, 1, 2, 3, 4, 5});
}

TEST(Constraints, ReleasingCrossedConstraintsKeepsTheCrossingVertex) {
    Tin tin = make_terrain(10);
    const VertexId a = tin.insert_point({2.0, 2.0}, 1.0);
    const VertexId b = tin.insert_point({8.0, 6.0}, 4.0);
    const VertexId c = tin.insert_point({3.0, 7.0}, 0.0);
    const VertexId d = tin.insert_point({7.0, 1.0}, 10.0);
    const ConstraintId ab = tin.insert_constraint(a, b, 1);
    const auto before = live_set(tin);
    const ConstraintId cd = tin.insert_constraint(c, d, 2);
    const auto created = new_vertices(before, tin);
    ASSERT_EQ(created.size(), 1u);
    const VertexId x = created[0];
    const double v0 = tin.volume();
    ASSERT_TRUE(tin.release_constraint(ab));
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    EXPECT_TRUE(tin.is_alive(x));
    EXPECT_TRUE(tin.is_on_constraint(x));
    EXPECT_EQ(tin.constraint(cd)->vertices, (std::vector<VertexId>{c, x, d}));
    expect_constrained_edges(tin, {edge(c, x), edge(x, d)});
    EXPECT_TRUE(test::tin_is_sound(tin));
    ASSERT_TRUE(tin.release_constraint(cd));
    EXPECT_FALSE(tin.is_on_constraint(x));
    EXPECT_EQ(tin.constrained_edge_count(), 0u);
    EXPECT_TRUE(tin.remove_vertex(x));
    EXPECT_LE(std::abs(tin.volume() - v0), 1e-12 * v0);
    EXPECT_TRUE(test::tin_is_sound(tin));
}

}  // namespace
}  // namespace sandtin
