// The relaxation's own vertex numbering (VertexNumbering, strips): a bijection onto the live
// vertices in strip order; a graph built in it (with or without room in its rows) matches the
// TIN through local edits; and the numbering changes no result: the Jacobi solver on a
// renumbered graph and arrays gives the heights of the TIN-id solver bit for bit, and
// SandPhysics in strip order gives the terrain of SandPhysics in TIN order bit for bit,
// through refinement, inserted and removed vertices and a renumbering.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "physics/sand_physics.hpp"
#include "physics/vertex_numbering.hpp"
#include "physics_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

TEST(VertexNumbering, StripsNumberEveryLiveVertexOnceInStripOrder) {
    Tin tin = Tin::random_points(Rect::from_size(2.0, 1.0), 5000, 3);
    // Some dead ids: they must not be numbered.
    const VertexArrays& va = tin.vertices();
    std::size_t removed = 0;
    for (std::uint32_t v = 0; v < va.size() && removed < 50; v += 37)
        removed += tin.remove_vertex(VertexId{v}) ? 1 : 0;
    ASSERT_GT(removed, 10u);
    VertexNumbering n;
    n.assign_strips(tin);
    EXPECT_FALSE(n.identity());
    ASSERT_EQ(n.size(), tin.vertex_count());
    EXPECT_EQ(n.appended(), 0u);
    const double strip = 2.0 * std::sqrt(2.0 / static_cast<double>(tin.vertex_count()));
    for (std::uint32_t l = 0; l < n.size(); ++l) {
        const std::uint32_t t = n.tin_id(l);
        ASSERT_TRUE(va.alive[t]);
        ASSERT_EQ(n.local(t), l);
        if (l == 0) continue;
        const Vec2 p = va.position[n.tin_id(l - 1)];
        const Vec2 q = va.position[t];
        const auto row_p = std::floor(p.y / strip);
        const auto row_q = std::floor(q.y / strip);
        ASSERT_TRUE(row_p < row_q || (row_p == row_q && p.x <= q.x)) << "local id " << l;
    }
    for (std::uint32_t t = 0; t < va.size(); ++t) {
        if (!va.alive[t]) {
            EXPECT_EQ(n.local(t), VertexNumbering::kNone);
        }
    }
    // A vertex born later goes to the end; a known one keeps its id.
    const std::uint32_t known = n.tin_id(7);
    EXPECT_EQ(n.add(known), 7u);
    const std::uint32_t born = n.add(static_cast<std::uint32_t>(va.size()) + 5);
    EXPECT_EQ(born, n.size() - 1);
    EXPECT_EQ(n.tin_id(born), va.size() + 5);
    EXPECT_EQ(n.appended(), 1u);

    VertexNumbering id;
    id.assign_identity(tin);
    EXPECT_TRUE(id.identity());
    EXPECT_EQ(id.size(), tin.vertex_capacity());
    EXPECT_EQ(id.add(tin.vertex_capacity() + 2), tin.vertex_capacity() + 2);
    EXPECT_EQ(id.tin_id(tin.vertex_capacity() + 1), tin.vertex_capacity() + 1);
    EXPECT_EQ(id.appended(), 0u);
}

TEST(VertexNumbering, RenumberedGraphHasTheSameRowsAndLengths) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 4);
    VertexNumbering n;
    n.assign_strips(tin);
    AdjacencyGraph own, local;
    own.rebuild(tin);
    local.rebuild(tin, &n);
    ASSERT_TRUE(own.matches(tin));
    ASSERT_TRUE(local.matches(tin, &n));
    EXPECT_FALSE(local.matches(tin));  // it really is another numbering
    auto same_rows = [&] {
        for (std::uint32_t l = 0; l < n.size(); ++l) {
            const std::uint32_t t = n.tin_id(l);
            if (local.degree(l) != own.degree(t)) return false;
            for (std::uint32_t k = 0; k < own.degree(t); ++k) {
                if (n.tin_id(local.targets()[local.offset(l) + k]) !=
                    own.targets()[own.offset(t) + k])
                    return false;
                if (std::memcmp(&local.lengths()[local.offset(l) + k],
                                &own.lengths()[own.offset(t) + k], sizeof(double)) != 0)
                    return false;
            }
        }
        return true;
    };
    EXPECT_TRUE(same_rows());
    // Local edits: born vertices are appended, dead ones keep an empty row.
    const std::uint32_t sub = tin.subscribe_vertex_changes();
    const std::vector<Vec2> points = {{0.31, 0.42}, {0.311, 0.43}, {0.7, 0.2}};
    tin.insert_points_on_surface(points);
    ASSERT_TRUE(tin.remove_vertex(VertexId{n.tin_id(100)}));
    const VertexChanges changes = tin.take_vertex_changes(sub);
    for (VertexId v : changes.topology) {
        if (tin.is_alive(v)) n.add(v.value);
    }
    EXPECT_EQ(n.appended(), 3u);
    own.update(tin, changes.topology);
    local.update(tin, changes.topology, &n);
    EXPECT_TRUE(own.matches(tin));
    EXPECT_TRUE(local.matches(tin, &n));
    EXPECT_TRUE(same_rows());
}

TEST(AdjacencyGraph, PackedRowsFollowLocalEdits) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 6);
    VertexNumbering n;
    n.assign_strips(tin);
    AdjacencyGraph packed(RowSlack::None), roomy;
    packed.rebuild(tin, &n);
    roomy.rebuild(tin, &n);
    std::size_t slots = 0;
    for (std::uint32_t v = 0; v < n.size(); ++v)
        slots += packed.degree(v);
    EXPECT_EQ(packed.slot_count(), slots);  // no empty slot
    EXPECT_GT(roomy.slot_count(), slots);
    const std::uint32_t sub = tin.subscribe_vertex_changes();
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(0.05, 0.95);
    for (int round = 0; round < 30; ++round) {
        std::vector<Vec2> points(40);
        for (Vec2& p : points)
            p = {u(rng), u(rng)};
        tin.insert_points_on_surface(points);
        for (int k = 0; k < 10; ++k) {
            const auto t = static_cast<std::uint32_t>(rng() % tin.vertex_capacity());
            if (tin.is_alive(VertexId{t})) tin.remove_vertex(VertexId{t});
        }
        const VertexChanges changes = tin.take_vertex_changes(sub);
        for (VertexId v : changes.topology) {
            if (tin.is_alive(v)) n.add(v.value);
        }
        packed.update(tin, changes.topology, &n);
        roomy.update(tin, changes.topology, &n);
        ASSERT_TRUE(packed.matches(tin, &n)) << "round " << round;
        ASSERT_TRUE(roomy.matches(tin, &n)) << "round " << round;
    }
}

TEST(AdjacencyGraph, AssignRefusesRowsWithoutTheirOppositeEdge) {
    AdjacencyGraph g;
    EXPECT_NO_THROW(g.assign({{1}, {0}}, {{0.5}, {0.5}}));
    EXPECT_THROW(g.assign({{1}, {}}, {{0.5}, {}}), std::invalid_argument);
    EXPECT_THROW(g.assign({{1}, {0}}, {{0.5}, {0.25}}), std::invalid_argument);
    EXPECT_THROW(g.assign({{2}, {0}}, {{0.5}, {0.5}}), std::invalid_argument);
    EXPECT_THROW(g.assign({{1}, {0}}, {{0.5}}), std::invalid_argument);
}

TEST(ActiveSet, RenumberKeepsTheOrderAndTheQuietCounts) {
    ActiveSet a;
    for (std::uint32_t v : {5u, 2u, 9u, 0u})
        a.activate(v);
    std::vector<std::uint8_t> changed(10, 0);
    changed[2] = 1;
    a.age(changed, 3);  // 5, 9, 0 one quiet iteration; 2 fresh
    // 5 -> 1, 2 -> 7, 9 -> dropped, 0 -> 3
    const std::vector<std::uint32_t> new_id = {3, 99, 7, 99, 99, 1, 99, 99, 99, 99};
    a.renumber(new_id, 99);
    EXPECT_EQ(a.list(), (std::vector<std::uint32_t>{1, 7, 3}));
    for (std::uint32_t v : {0u, 2u, 5u, 9u})
        EXPECT_FALSE(a.contains(v));
    // Two more quiet iterations: 1 and 3 (one quiet already) leave, 7 stays.
    std::fill(changed.begin(), changed.end(), 0);
    a.age(changed, 3);
    a.age(changed, 3);
    EXPECT_EQ(a.list(), (std::vector<std::uint32_t>{7}));
}

/// The Jacobi solver on the strip-renumbered graph and arrays (with the TIN ids for the
/// jitter) against the solver on TIN ids: heights, changed vertices, active sets and split
/// requests must agree bit for bit / as sets, mapped through the numbering.
void compare_solver(int threads, double randomness, double relocation_radius) {
    SCOPED_TRACE(::testing::Message() << "threads " << threads << ", randomness " << randomness
                                      << ", r_S " << relocation_radius);
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 6000, 5);
    const VertexArrays& va = tin.vertices();
    const std::size_t n = va.size();
    VertexNumbering num;
    num.assign_strips(tin);
    ASSERT_EQ(num.size(), n);
    AdjacencyGraph own, local;
    own.rebuild(tin);
    local.rebuild(tin, &num);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> h(n), b(n, -1e9), tan(n);
    for (std::size_t v = 0; v < n; ++v) {
        h[v] = test::rough_sand(va.position[v]) + 0.02 * u(rng);
        b[v] = h[v] - (u(rng) < 0.3 ? 0.0 : 0.01 * u(rng));
        tan[v] = 0.5 + 0.3 * u(rng);
    }
    std::vector<double> hl(n), al(n), bl(n), tl(n);
    for (std::uint32_t l = 0; l < n; ++l) {
        const std::uint32_t t = num.tin_id(l);
        hl[l] = h[t], al[l] = va.lumped_area[t], bl[l] = b[t], tl[l] = tan[t];
    }
    TalusSettings settings = seeds_rule();  // more of the scene moves
    settings.schedule = Schedule::Jacobi;
    settings.threads = threads;
    settings.randomness = randomness;
    settings.seed = 9;
    settings.parameters.relocation_radius = relocation_radius;
    TalusSolver by_id(settings), by_strip(settings);
    const TalusArrays arrays{h.data(), va.lumped_area.data(), b.data(), tan.data(), n};
    const TalusArrays local_arrays{hl.data(), al.data(), bl.data(),
                                   tl.data(), n,         num.tin_ids().data()};
    std::vector<std::uint32_t> all(n);
    for (std::uint32_t v = 0; v < n; ++v)
        all[v] = v;
    std::shuffle(all.begin(), all.end(), rng);
    ActiveSet active, local_active;
    for (std::uint32_t v : all) {
        active.activate(v);
        local_active.activate(num.local(v));
    }
    auto to_tin = [&](const std::vector<std::uint32_t>& ls) {
        std::vector<std::uint32_t> ts;
        for (std::uint32_t l : ls)
            ts.push_back(num.tin_id(l));
        return test::sorted_ids(ts);
    };
    std::size_t moving = 0;
    for (int it = 0; it < 200 && !active.empty(); ++it) {
        std::vector<std::uint32_t> splits, local_splits;
        const IterationStats s = by_id.iterate(own, arrays, active, &splits);
        const IterationStats r = by_strip.iterate(local, local_arrays, local_active, &local_splits);
        ASSERT_EQ(s.processed, r.processed) << "iteration " << it;
        ASSERT_EQ(s.changed, r.changed) << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(by_id.changed()), to_tin(by_strip.changed()))
            << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(active.list()), to_tin(local_active.list()))
            << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(splits), to_tin(local_splits)) << "iteration " << it;
        for (std::uint32_t l = 0; l < n; ++l)
            ASSERT_EQ(std::memcmp(&hl[l], &h[num.tin_id(l)], sizeof(double)), 0)
                << "iteration " << it << ", vertex " << num.tin_id(l);
        moving += s.changed;
    }
    EXPECT_GT(moving, n);
}

TEST(VertexNumbering, RenumberedJacobiSolverGivesTheSameHeightsBitForBit) {
    for (int threads : {1, 2}) {
        compare_solver(threads, 0.0, 0.0);
        compare_solver(threads, 0.4, 0.0);
        compare_solver(threads, 0.0, 0.012);
    }
}

/// Two copies of one scene, relaxed by SandPhysics in TIN order and in strip order, with the
/// relocation radius refining, points inserted (enough to renumber) and vertices removed
/// between steps: the TINs must stay identical bit for bit.
void compare_physics(Schedule schedule, double randomness, double relocation_radius) {
    SCOPED_TRACE(::testing::Message()
                 << "schedule " << static_cast<int>(schedule) << ", randomness " << randomness
                 << ", r_S " << relocation_radius);
    Tin by_id = Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 8);
    Tin by_strip = Tin::random_points(Rect::from_size(1.0, 1.0), 2000, 8);
    for (Tin* tin : {&by_id, &by_strip}) {
        const VertexArrays& va = tin->vertices();
        for (std::uint32_t v = 0; v < va.size(); ++v) {
            if (!va.alive[v]) continue;
            const double h = test::rough_sand(va.position[v]);
            tin->set_height(VertexId{v}, h);
            if (v % 3 == 0) tin->set_bedrock(VertexId{v}, h - 0.01);
        }
    }
    TalusSettings settings;
    settings.schedule = schedule;
    settings.threads = 2;
    settings.randomness = randomness;
    settings.seed = 4;
    settings.parameters.relocation_radius = relocation_radius;
    SandPhysics a(by_id, MaterialTable::presets(), settings, VertexOrder::Tin);
    SandPhysics b(by_strip, MaterialTable::presets(), settings, VertexOrder::Strips);
    EXPECT_TRUE(a.numbering().identity());
    EXPECT_FALSE(b.numbering().identity());
    a.activate_all();
    b.activate_all();
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(0.05, 0.95);
    std::size_t moved = 0;
    for (int round = 0; round < 8; ++round) {
        if (round == 2) {
            // Born vertices: more than kRenumberMinimum, so the strip physics renumbers.
            std::vector<Vec2> points(SandPhysics::kRenumberMinimum + 500);
            for (Vec2& p : points)
                p = {u(rng), u(rng)};
            by_id.insert_points_on_surface(points);
            by_strip.insert_points_on_surface(points);
        }
        if (round == 4) {
            const VertexArrays& va = by_id.vertices();
            for (std::uint32_t v = 11; v < va.size(); v += 97) {
                const bool ra = by_id.remove_vertex(VertexId{v});
                const bool rb = by_strip.remove_vertex(VertexId{v});
                ASSERT_EQ(ra, rb);
            }
        }
        std::vector<VertexId> ca, cb;
        const PhysicsStepReport ra = a.step(15, &ca);
        const PhysicsStepReport rb = b.step(15, &cb);
        ASSERT_EQ(ra.iterations, rb.iterations) << "round " << round;
        ASSERT_EQ(ra.vertex_updates, rb.vertex_updates) << "round " << round;
        ASSERT_EQ(ra.changed, rb.changed) << "round " << round;
        ASSERT_EQ(ra.refined, rb.refined) << "round " << round;
        ASSERT_EQ(a.active_count(), b.active_count()) << "round " << round;
        std::sort(ca.begin(), ca.end());
        std::sort(cb.begin(), cb.end());
        ASSERT_EQ(ca, cb) << "round " << round;
        const VertexArrays& va = by_id.vertices();
        const VertexArrays& vb = by_strip.vertices();
        ASSERT_EQ(va.size(), vb.size());
        for (std::uint32_t v = 0; v < va.size(); ++v) {
            ASSERT_EQ(va.alive[v], vb.alive[v]) << "round " << round << ", vertex " << v;
            if (!va.alive[v]) continue;
            ASSERT_EQ(std::memcmp(&va.height[v], &vb.height[v], sizeof(double)), 0)
                << "round " << round << ", vertex " << v;
            ASSERT_EQ(a.is_active(VertexId{v}), b.is_active(VertexId{v}));
        }
        moved += rb.changed;
    }
    EXPECT_GE(b.renumberings(), 1u);
    EXPECT_EQ(a.renumberings(), 0u);
    EXPECT_TRUE(b.graph().matches(by_strip, &b.numbering()));
    EXPECT_TRUE(a.graph().matches(by_id, &a.numbering()));
    EXPECT_GT(moved, 2000u);
}

TEST(VertexNumbering, SandPhysicsPicksStripsForJacobiAndTinIdsForSequential) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 500, 2);
    TalusSettings settings;
    settings.schedule = Schedule::Jacobi;
    EXPECT_FALSE(SandPhysics(tin, MaterialTable::presets(), settings).numbering().identity());
    settings.schedule = Schedule::Sequential;
    EXPECT_TRUE(SandPhysics(tin, MaterialTable::presets(), settings).numbering().identity());
    EXPECT_FALSE(SandPhysics(tin, MaterialTable::presets(), settings, VertexOrder::Strips)
                     .numbering()
                     .identity());
}

TEST(VertexNumbering, SandPhysicsInStripOrderGivesTheTerrainOfTinOrderBitForBit) {
    compare_physics(Schedule::Jacobi, 0.0, 0.0);
    compare_physics(Schedule::Jacobi, 0.3, 0.02);
    compare_physics(Schedule::Sequential, 0.3, 0.02);
}

}  // namespace
}  // namespace sandtin
