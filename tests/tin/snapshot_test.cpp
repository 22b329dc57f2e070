// Snapshots: exact restore (including cocircular grids and constraint crossings), and
// rejection of corrupted snapshots with std::runtime_error.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

double ripples(Vec2 p) {
    return 1.5 + 0.2 * std::sin(3.0 * p.x) + 0.1 * std::cos(2.0 * p.y);
}

/// Restores and expects the identical snapshot back. lumped_area is recomputed on restore
/// (it is not stored in session files), so it is compared to 1e-12 relative.
void expect_round_trip(const Tin& tin) {
    const TinSnapshot s = tin.snapshot();
    const Tin copy = Tin::from_snapshot(s);
    test::expect_snapshots_equal(s, copy.snapshot(), 1e-12);
    EXPECT_TRUE(copy.check_valid().ok()) << copy.check_valid().summary();
    EXPECT_EQ(copy.vertex_count(), tin.vertex_count());
    EXPECT_EQ(copy.triangle_count(), tin.triangle_count());
    EXPECT_EQ(copy.constrained_edge_count(), tin.constrained_edge_count());
    EXPECT_EQ(copy.constraint_count(), tin.constraint_count());
    EXPECT_TRUE(test::close_rel(copy.volume(), tin.volume(), 1e-12));
    for (TriangleSlot t = 0; t < tin.slot_capacity(); ++t) {
        EXPECT_EQ(copy.slot_constraint_mask(t), tin.slot_constraint_mask(t)) << "slot " << t;
    }
}

/// A terrain with free ids and slots, constraints with crossings, and set attributes.
Tin busy_terrain() {
    Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 300, 3, ripples);
    tin.take_changes();
    const VertexId a = tin.insert_point({2.0, 2.0}, 1.0);
    const VertexId b = tin.insert_point({8.0, 6.0}, 4.0);
    const VertexId c = tin.insert_point({3.0, 7.0}, 0.0);
    const VertexId d = tin.insert_point({7.0, 1.0}, 3.0);
    tin.insert_constraint(a, b, 1);
    tin.insert_constraint(c, d, 2);
    std::vector<VertexId> ring;
    for (int i = 0; i < 6; ++i) {
        const double ang = i * 1.0471975511965976;
        ring.push_back(
            tin.insert_point_on_surface({5.0 + 1.2 * std::cos(ang), 4.0 + 1.2 * std::sin(ang)}));
    }
    tin.insert_constraint(ring, true, 3);
    const VertexId e = tin.insert_point({0.5, 9.0}, 1.0);
    const VertexId f = tin.insert_point({1.5, 9.5}, 1.0);
    const ConstraintId gone = tin.insert_constraint(e, f, 4);
    tin.release_constraint(gone);  // a free constraint id
    for (VertexId v : test::live_ids(tin)) {
        if (v.value % 11 == 0 && !tin.is_boundary(v) && !tin.is_on_constraint(v))
            tin.remove_vertex(v);
        if (!tin.is_alive(v)) continue;
        if (v.value % 7 == 0) tin.set_material(v, static_cast<std::uint16_t>(v.value % 5));
        if (v.value % 5 == 0) tin.set_moisture(v, 0.125f * static_cast<float>(v.value % 8));
        if (v.value % 3 == 0) tin.set_slide(v, {0.25f, 0.5f});
        if (v.value % 4 == 0) tin.set_bedrock(v, tin.height(v) - 0.5);
        if (v.value % 6 == 0) tin.set_water_depth(v, 0.001 * static_cast<double>(v.value % 9));
    }
    return tin;
}

TEST(Snapshot, RoundTripRandomTerrain) {
    expect_round_trip(Tin::random_points(Rect{{-3.0, -2.0}, {4.0, 5.0}}, 1000, 1, ripples));
}

TEST(Snapshot, RoundTripRegularGridKeepsDiagonals) {
    // Every cell of a grid is cocircular: re-inserting the points could pick other diagonals.
    Tin tin = Tin::regular_grid(Rect::from_size(5.0, 5.0), 25, 25, ripples);
    expect_round_trip(tin);
    // Also after edits that flip diagonals, and with constraints along the grid lines.
    std::mt19937_64 rng = test::test_rng(2);
    std::uniform_real_distribution<double> u(0.0, 5.0);
    for (int i = 0; i < 50; ++i)
        tin.insert_point_on_surface({u(rng), u(rng)});
    const Location a = tin.locate({1.0, 1.0});
    const Location b = tin.locate({4.0, 1.0});
    tin.insert_constraint(a.corners[0], b.corners[0], 1);
    expect_round_trip(tin);
    EXPECT_EQ(test::triangle_set(Tin::from_snapshot(tin.snapshot())), test::triangle_set(tin));
}

TEST(Snapshot, RoundTripWithConstraintsCrossingsAndFreeLists) {
    Tin tin = busy_terrain();
    // Pending (unreported) deaths are part of the hand-out order.
    expect_round_trip(tin);
    tin.take_changes();
    expect_round_trip(tin);
    const TinSnapshot s = tin.snapshot();
    EXPECT_FALSE(s.vertex_free_list.empty());
    EXPECT_FALSE(s.constraint_free_list.empty());
    EXPECT_EQ(s.constraints.size(), 3u);
}

TEST(Snapshot, RoundTripWithAConstraintNextToAnotherConstraintsVertex) {
    // b1-b2 is constrained although not Delaunay (v and w lie close above and below it), and
    // v is the end of an earlier constraint. Restoring must keep every edge as saved.
    Tin tin = Tin::flat_rectangle(Rect::from_size(10.0, 10.0), 1.0);
    const VertexId v = tin.insert_point({5.0, 5.5}, 1.0);
    tin.insert_point({5.0, 4.5}, 1.0);
    const VertexId u = tin.insert_point({5.0, 8.0}, 1.0);
    const VertexId b1 = tin.insert_point({2.0, 5.0}, 1.0);
    const VertexId b2 = tin.insert_point({8.0, 5.0}, 1.0);
    tin.insert_constraint(v, u, 1);
    tin.insert_constraint(b1, b2, 2);
    ASSERT_TRUE(tin.check_valid().ok());
    ASSERT_TRUE(tin.is_constrained_edge(b1, b2));
    ASSERT_NO_THROW(expect_round_trip(tin));
}

// VertexArrays' copy (it prepares its storage for writing rather than copying vector by
// vector): every array equal, the copy independent of its source, and self-assignment a no-op.
TEST(Snapshot, VertexArraysCopyEveryArrayAndStayIndependent) {
    const Tin tin = busy_terrain();
    const VertexArrays& from = tin.vertices();
    const auto same = [](const VertexArrays& a, const VertexArrays& b) {
        return a.position == b.position && a.height == b.height && a.bedrock == b.bedrock &&
               a.material == b.material && a.moisture == b.moisture && a.slide == b.slide &&
               a.water_depth == b.water_depth && a.lumped_area == b.lumped_area &&
               a.alive == b.alive;
    };
    VertexArrays copy(from);
    EXPECT_TRUE(same(copy, from));
    VertexArrays assigned;
    assigned.resize(3);  // smaller storage, grown by the assignment
    assigned = from;
    EXPECT_TRUE(same(assigned, from));
    VertexArrays larger;
    larger.resize(from.size() * 2);  // larger storage, shrunk to the source's length
    larger = from;
    EXPECT_TRUE(same(larger, from));
    const double height0 = from.height[0];
    const std::uint8_t alive1 = from.alive[1];
    copy.height[0] += 1.0;
    copy.alive[1] = alive1 == 0 ? 1 : 0;
    EXPECT_EQ(from.height[0], height0);
    EXPECT_EQ(from.alive[1], alive1);
    VertexArrays& self = assigned;
    assigned = self;
    EXPECT_TRUE(same(assigned, from));
}

TEST(Snapshot, RestoredTinKeepsEditingLikeTheOriginal) {
    Tin a = busy_terrain();
    a.take_changes();
    Tin b = Tin::from_snapshot(a.snapshot());
    b.take_changes();
    // Same edits on both: the ids handed out and the triangulations agree.
    std::mt19937_64 rng = test::test_rng(4);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    for (int i = 0; i < 100; ++i) {
        const Vec2 p{u(rng), u(rng)};
        EXPECT_EQ(a.insert_point(p, 3.0), b.insert_point(p, 3.0));
    }
    for (VertexId v : test::live_ids(a)) {
        if (v.value % 9 == 0 && !a.is_boundary(v) && !a.is_on_constraint(v)) {
            EXPECT_TRUE(a.remove_vertex(v, VolumePolicy::Report));
            EXPECT_TRUE(b.remove_vertex(v, VolumePolicy::Report));
        }
    }
    a.take_changes();
    b.take_changes();
    for (int i = 0; i < 10; ++i) {
        const Vec2 p{u(rng), u(rng)};
        EXPECT_EQ(a.insert_point(p, 3.0), b.insert_point(p, 3.0));
    }
    EXPECT_EQ(test::triangle_set(a), test::triangle_set(b));
    EXPECT_EQ(a.vertices().height, b.vertices().height);
    EXPECT_TRUE(b.check_valid().ok());
}

TEST(Snapshot, ReinsertingAConstraintAfterRestoreReturnsItsId) {
    Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 100, 5, ripples);
    const VertexId a = tin.insert_point({2.0, 2.0}, 1.0);
    const VertexId b = tin.insert_point({6.0, 3.0}, 1.0);
    const ConstraintId id = tin.insert_constraint(a, b, 4);
    Tin copy = Tin::from_snapshot(tin.snapshot());
    EXPECT_EQ(copy.insert_constraint(a, b, 6), id);
    EXPECT_EQ(copy.constraint_count(), 1u);
    EXPECT_TRUE(copy.check_valid().ok());
}

// ---- Corrupted snapshots ----------------------------------------------------------------

/// Expects from_snapshot to throw std::runtime_error (and nothing worse).
void expect_rejected(const TinSnapshot& s, const std::string& what) {
    try {
        const Tin t = Tin::from_snapshot(s);
        ADD_FAILURE() << what << ": accepted; check_valid says: " << t.check_valid().summary();
    } catch (const std::runtime_error& e) {
        EXPECT_GT(std::string(e.what()).size(), 10u) << what;
    } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": wrong exception type: " << e.what();
    }
}

class CorruptSnapshot : public ::testing::Test {
  protected:
    void SetUp() override {
        tin_ = std::make_unique<Tin>(busy_terrain());
        tin_->take_changes();
        good = tin_->snapshot();
        ASSERT_NO_THROW((void)Tin::from_snapshot(good));
        for (std::uint32_t i = 0; i < good.vertices.size(); ++i) {
            if (good.vertices.alive[i]) {
                if (live == kNone) live = i;
            } else if (dead == kNone) {
                dead = i;
            }
        }
        for (std::uint32_t t = 0; t < good.slots.size(); ++t) {
            const auto& c = good.slots[t];
            if (c[0] == kNoSlot) continue;
            const bool finite =
                c[0] < kOutsideCorner && c[1] < kOutsideCorner && c[2] < kOutsideCorner;
            if (finite && finite_slot == kNone) finite_slot = t;
            if (!finite && outer_slot == kNone) outer_slot = t;
        }
        ASSERT_NE(dead, kNone);
        ASSERT_NE(finite_slot, kNone);
        ASSERT_NE(outer_slot, kNone);
    }

    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    std::unique_ptr<Tin> tin_;
    TinSnapshot good;
    std::uint32_t live = kNone, dead = kNone, finite_slot = kNone, outer_slot = kNone;
};

TEST_F(CorruptSnapshot, TriangleNamingADeadVertex) {
    TinSnapshot s = good;
    s.slots[finite_slot][1] = dead;
    expect_rejected(s, "dead corner");
    s = good;
    s.slots[finite_slot][2] = static_cast<std::uint32_t>(s.vertices.size() + 5);
    expect_rejected(s, "unknown corner");
}

TEST_F(CorruptSnapshot, FlippedTriangleOrientation) {
    TinSnapshot s = good;
    std::swap(s.slots[finite_slot][0], s.slots[finite_slot][1]);
    expect_rejected(s, "flipped finite triangle");
    s = good;
    std::swap(s.slots[outer_slot][0], s.slots[outer_slot][1]);
    expect_rejected(s, "flipped outer triangle");
}

// A flipped diagonal leaves a valid triangulation that is not Delaunay. check_valid's own
// in-circle loop is what must catch it (CGAL's structural is_valid does not look at circles).
TEST_F(CorruptSnapshot, FlippedDiagonalIsNotLocallyDelaunay) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> constrained;
    for (const ConstraintRecord& c : good.constraints) {
        for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
            constrained.insert({c.vertices[k], c.vertices[k + 1]});
            constrained.insert({c.vertices[k + 1], c.vertices[k]});
        }
    }
    const auto& pos = good.vertices.position;
    const auto orient = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        return cross(pos[b] - pos[a], pos[c] - pos[a]);
    };
    // Slots s = (a, b, c) and t = (b, a, d), both counter-clockwise, sharing the unconstrained
    // edge a-b, with d clearly outside the circle through a, b, c and the quad a d b c convex:
    // flipping to (a, d, c), (d, b, c) then makes d clearly inside, a non-Delaunay edge c-d.
    for (std::uint32_t s = 0; s < good.slots.size(); ++s) {
        const auto cs = good.slots[s];
        if (cs[0] >= kOutsideCorner || cs[1] >= kOutsideCorner || cs[2] >= kOutsideCorner) continue;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = cs[k], b = cs[(k + 1) % 3], c = cs[(k + 2) % 3];
            if (constrained.count({a, b})) continue;
            for (std::uint32_t t = 0; t < good.slots.size(); ++t) {
                const auto ct = good.slots[t];
                if (t == s || ct[0] >= kOutsideCorner || ct[1] >= kOutsideCorner ||
                    ct[2] >= kOutsideCorner)
                    continue;
                for (int j = 0; j < 3; ++j) {
                    if (ct[j] != b || ct[(j + 1) % 3] != a) continue;
                    const std::uint32_t d = ct[(j + 2) % 3];
                    const double scale = length_squared(pos[a] - pos[b]);
                    if (!(orient(a, d, c) > 0.05 * scale && orient(d, b, c) > 0.05 * scale))
                        continue;
                    if (!(test::relative_in_circle(pos[a], pos[b], pos[c], pos[d]) < -1e-3L))
                        continue;
                    TinSnapshot flipped = good;
                    flipped.slots[s] = {a, d, c};
                    flipped.slots[t] = {d, b, c};
                    try {
                        (void)Tin::from_snapshot(flipped);
                        FAIL() << "a flipped non-Delaunay diagonal was accepted";
                    } catch (const std::runtime_error& e) {
                        EXPECT_NE(std::string(e.what()).find("not locally Delaunay"),
                                  std::string::npos)
                            << e.what();
                    }
                    return;
                }
            }
        }
    }
    FAIL() << "no flippable unconstrained edge found";
}

TEST_F(CorruptSnapshot, InconsistentFreeLists) {
    TinSnapshot s = good;
    s.vertex_free_list.push_back(live);
    expect_rejected(s, "live id in the free list");
    s = good;
    s.vertex_free_list.pop_back();
    expect_rejected(s, "dead id missing from the free list");
    s = good;
    s.vertex_free_list.back() = s.vertex_free_list.front();
    if (s.vertex_free_list.size() > 1) expect_rejected(s, "repeated free id");
    s = good;
    s.vertex_free_list.push_back(static_cast<std::uint32_t>(s.vertices.size()));
    expect_rejected(s, "out-of-range free id");
    s = good;
    s.slot_free_list.push_back(finite_slot);
    expect_rejected(s, "live slot in the free list");
    s = good;
    s.constraint_free_list.clear();
    expect_rejected(s, "constraint free list missing an id");
    s = good;
    s.constraint_free_list.push_back(s.constraints.front().id);
    expect_rejected(s, "live constraint id in the free list");
}

TEST_F(CorruptSnapshot, ArrayLengthMismatch) {
    TinSnapshot s = good;
    s.vertices.moisture.pop_back();
    expect_rejected(s, "moisture shorter");
    s = good;
    s.vertices.position.push_back({1.0, 1.0});
    expect_rejected(s, "position longer");
    s = good;
    s.vertices.alive.pop_back();
    expect_rejected(s, "alive shorter");
    s = good;
    s.vertices.slide.clear();
    expect_rejected(s, "slide empty");
}

TEST_F(CorruptSnapshot, BadVertexValues) {
    TinSnapshot s = good;
    s.vertices.height[live] = std::numeric_limits<double>::quiet_NaN();
    expect_rejected(s, "NaN height");
    s = good;
    s.vertices.position[live] = {-100.0, 5.0};
    expect_rejected(s, "vertex outside the domain");
    s = good;
    s.vertices.moisture[live] = 2.0f;
    expect_rejected(s, "moisture above 1");
    s = good;
    s.vertices.water_depth[live] = -1e-3;
    expect_rejected(s, "negative water depth");
    s = good;
    s.vertices.water_depth[live] = std::numeric_limits<double>::infinity();
    expect_rejected(s, "infinite water depth");
    s = good;
    s.vertices.water_depth.pop_back();
    expect_rejected(s, "water depths shorter");
    s = good;
    s.vertices.alive[live] = 2;
    expect_rejected(s, "alive flag 2");
    s = good;
    s.vertices.alive[live] = 0;
    expect_rejected(s, "a used vertex marked dead");
    s = good;
    s.vertices.bedrock[live] = s.vertices.height[live] + 1.0;
    expect_rejected(s, "bedrock above the surface");
}

TEST_F(CorruptSnapshot, MovedVertexBreaksGeometry) {
    // Move an interior vertex far across its neighbours: triangles fold over.
    TinSnapshot s = good;
    for (std::uint32_t i = 0; i < s.vertices.size(); ++i) {
        if (!s.vertices.alive[i] || test::on_domain_border(s.domain, s.vertices.position[i]))
            continue;
        const Vec2 p = s.vertices.position[i];
        s.vertices.position[i] = {10.0 - p.x, 10.0 - p.y};
        break;
    }
    expect_rejected(s, "vertex moved across the mesh");
}

TEST_F(CorruptSnapshot, MissingOrDuplicatedTriangles) {
    TinSnapshot s = good;
    s.slots[finite_slot] = {kNoSlot, kNoSlot, kNoSlot};
    s.slot_free_list.push_back(finite_slot);
    expect_rejected(s, "a hole");
    s = good;
    s.slots.push_back(s.slots[finite_slot]);
    expect_rejected(s, "a duplicated triangle");
    s = good;
    s.slots[finite_slot][1] = s.slots[finite_slot][0];
    expect_rejected(s, "a repeated corner");
    s = good;
    s.slots[outer_slot] = {
        kOutsideCorner, kOutsideCorner,
        s.slots[outer_slot][0] == kOutsideCorner ? s.slots[outer_slot][1] : s.slots[outer_slot][0]};
    expect_rejected(s, "two corners at infinity");
    s = good;
    s.slots.clear();
    s.slot_free_list.clear();
    expect_rejected(s, "no triangles");
}

TEST_F(CorruptSnapshot, BadConstraints) {
    TinSnapshot s = good;
    s.constraints[0].vertices = {s.constraints[0].vertices.front()};
    expect_rejected(s, "one-vertex constraint");
    s = good;
    s.constraints[0].vertices.push_back(dead);
    expect_rejected(s, "constraint through a dead vertex");
    s = good;
    s.constraints[1].id = s.constraints[0].id;
    expect_rejected(s, "repeated constraint id");
    s = good;
    s.constraints[0].id = s.constraint_capacity + 3;
    expect_rejected(s, "constraint id out of range");
    s = good;
    // A constraint between two vertices that share no edge.
    std::uint32_t far_a = kNone, far_b = kNone;
    for (std::uint32_t i = 0; i < s.vertices.size(); ++i) {
        if (!s.vertices.alive[i]) continue;
        const Vec2 p = s.vertices.position[i];
        if (p == Vec2{0.0, 0.0}) far_a = i;
        if (p == Vec2{10.0, 10.0}) far_b = i;
    }
    ASSERT_NE(far_a, kNone);
    ASSERT_NE(far_b, kNone);
    s.constraints[0].vertices = {far_a, far_b};
    expect_rejected(s, "constraint along no edge");
}

TEST_F(CorruptSnapshot, BadDomain) {
    TinSnapshot s = good;
    s.domain.max.x = s.domain.min.x;
    expect_rejected(s, "zero-width domain");
    s = good;
    s.domain.max.y = std::numeric_limits<double>::quiet_NaN();
    expect_rejected(s, "NaN domain");
    s = good;
    s.domain = Rect{{-1.0, -1.0}, {11.0, 11.0}};  // larger than the triangles
    expect_rejected(s, "domain larger than the mesh");
}

TEST_F(CorruptSnapshot, RandomMutationsNeverCrash) {
    // Random single-field mutations: each is either rejected with std::runtime_error or yields
    // a terrain that passes check_valid().
    std::mt19937_64 rng = test::test_rng(99);
    int rejected = 0;
    int accepted = 0;
    std::uniform_real_distribution<double> nudge(-0.4, 0.4);
    for (int trial = 0; trial < 600; ++trial) {
        TinSnapshot s = good;
        const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
        switch (trial % 8) {
            case 0:
                s.slots[pick(s.slots.size())][pick(3)] =
                    static_cast<std::uint32_t>(pick(s.vertices.size() + 3));
                break;
            case 1:
                s.slots[pick(s.slots.size())][pick(3)] = kOutsideCorner;
                break;
            case 2: {
                auto& c = s.slots[pick(s.slots.size())];
                std::swap(c[pick(3)], c[pick(3)]);
                break;
            }
            case 3: {
                const std::size_t i = pick(s.vertices.size());
                s.vertices.position[i] = s.vertices.position[pick(s.vertices.size())];
                break;
            }
            case 4: {
                auto& vs = s.constraints[pick(s.constraints.size())].vertices;
                vs[pick(vs.size())] = static_cast<std::uint32_t>(pick(s.vertices.size()));
                break;
            }
            case 5:
                std::swap(s.slots[pick(s.slots.size())], s.slots[pick(s.slots.size())]);
                break;
            case 6: {
                // A vertex nudged by up to 0.4 m (the mean spacing is about 0.6 m): some moves
                // keep every triangle counter-clockwise but make an edge non-Delaunay, some
                // fold a triangle over, some change nothing that matters.
                const std::size_t i = pick(s.vertices.size());
                const Vec2 p = s.vertices.position[i];
                const Vec2 q{p.x + nudge(rng), p.y + nudge(rng)};
                if (s.domain.contains(q) && !test::on_domain_border(s.domain, p))
                    s.vertices.position[i] = q;
                break;
            }
            default: {
                // A corner swapped for a corner of another triangle.
                auto& c = s.slots[pick(s.slots.size())];
                const auto& other = s.slots[pick(s.slots.size())];
                c[pick(3)] = other[pick(3)];
                break;
            }
        }
        try {
            const Tin t = Tin::from_snapshot(s);
            ++accepted;
            const ValidationReport r = t.check_valid();
            EXPECT_TRUE(r.ok()) << "trial " << trial
                                << " accepted an invalid terrain: " << r.summary();
        } catch (const std::runtime_error&) {
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 200);
    EXPECT_GT(accepted, 0);  // some mutations are harmless (e.g. swapping two live slots)
}

// The restore checks its triangles in ranges spread over the cores: a damaged triangle or
// vertex late in a large snapshot (another thread's range on a multi-core machine) is refused
// as one early in it is, by name.
TEST(Snapshot, DamageAnywhereInALargeSnapshotIsRefusedByName) {
    const Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 20000, 12, ripples);
    const TinSnapshot good = tin.snapshot();
    std::vector<std::uint32_t> finite_slots;
    for (std::uint32_t t = 0; t < good.slots.size(); ++t) {
        const auto& c = good.slots[t];
        if (c[0] < kOutsideCorner && c[1] < kOutsideCorner && c[2] < kOutsideCorner)
            finite_slots.push_back(t);
    }
    ASSERT_GT(finite_slots.size(), 30000u);
    for (const std::uint32_t t :
         {finite_slots.front(), finite_slots[finite_slots.size() / 2], finite_slots.back()}) {
        TinSnapshot s = good;
        std::swap(s.slots[t][0], s.slots[t][1]);  // clockwise, and its edges' twins gone
        try {
            (void)Tin::from_snapshot(s);
            ADD_FAILURE() << "a flipped triangle in slot " << t << " was accepted";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("invalid terrain data"), std::string::npos);
        }
    }
    // A non-Delaunay edge deep in the terrain: the diagonal of two triangles late in slot
    // order flipped, where they form a convex quadrilateral (both new triangles stay
    // counter-clockwise, so only the in-circle test can tell).
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> slot_of_edge;
    for (const std::uint32_t t : finite_slots) {
        for (int i = 0; i < 3; ++i)
            slot_of_edge[{good.slots[t][(i + 1) % 3], good.slots[t][(i + 2) % 3]}] = t;
    }
    for (std::size_t k = finite_slots.size(); k-- > 0;) {
        const std::uint32_t ta = finite_slots[k];
        for (int i = 0; i < 3; ++i) {
            const auto& a = good.slots[ta];
            const std::uint32_t p = a[(i + 1) % 3], q = a[(i + 2) % 3], x = a[i];
            const auto twin = slot_of_edge.find({q, p});
            if (twin == slot_of_edge.end()) continue;
            const auto& b = good.slots[twin->second];
            const std::uint32_t y = b[0] != p && b[0] != q   ? b[0]
                                    : b[1] != p && b[1] != q ? b[1]
                                                             : b[2];
            const Vec2 px = good.vertices.position[p], qx = good.vertices.position[q];
            const Vec2 xx = good.vertices.position[x], yx = good.vertices.position[y];
            if (cross(px - xx, yx - xx) <= 0.0 || cross(qx - yx, xx - yx) <= 0.0) continue;
            TinSnapshot s = good;
            s.slots[ta] = {x, p, y};
            s.slots[twin->second] = {y, q, x};
            try {
                (void)Tin::from_snapshot(s);
                ADD_FAILURE() << "a flipped diagonal at slot " << ta << " was accepted";
            } catch (const std::runtime_error& e) {
                EXPECT_NE(std::string(e.what()).find("not locally Delaunay"), std::string::npos)
                    << e.what();
            }
            return;
        }
    }
    ADD_FAILURE() << "found no diagonal to flip";
}

}  // namespace
}  // namespace sandtin
