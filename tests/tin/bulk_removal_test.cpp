// remove_in_patches: bulk removal of offered vertices, a connected patch at a time. Oracles:
// the offered set and the pre-edit neighbourhoods (which vertices died, which were on a
// constraint or the border, who was next to a constrained vertex), the brute-force volume,
// the disc test of support/region_oracles.hpp, and the CGAL-free mesh checks.
// Which vertices go is compared with a brute-force reference of the drop rule: full passes
// over the set, repeated until nothing changes.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "support/region_oracles.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/bulk_removal.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::in_disc;
using test::live_ids;

void constrain(Tin& tin, const std::vector<Vec2>& pts, bool closed, Generation generation) {
    std::vector<double> hs;
    for (Vec2 p : pts)
        hs.push_back(test::bumpy_sand(p));
    const std::vector<VertexId> ids = tin.insert_points(pts, hs);
    tin.insert_constraint(ids, closed, generation);
}

/// Runs remove_in_patches and checks everything that must hold whatever it decides: only
/// offered, interior, unconstrained vertices die, and none that was next to a constrained
/// vertex; nothing else moves; the counts, the report and the volume agree.
/// With `may_border`, also: every removed vertex's surviving neighbours satisfy it.
BulkRemoval clear_and_check(
    Tin& tin, const std::vector<VertexId>& offered,
    const std::function<bool(VertexId v, VertexId w)>& may_border = nullptr) {
    const std::set<VertexId> offer(offered.begin(), offered.end());
    std::set<VertexId>
        protected_vertices;  // on a constraint or the border, or next to a constraint
    for (VertexId v : live_ids(tin)) {
        if (!tin.is_on_constraint(v) && !tin.is_boundary(v)) continue;
        protected_vertices.insert(v);
        if (!tin.is_on_constraint(v)) continue;
        std::vector<VertexId> around;
        tin.neighbours(v, around);
        protected_vertices.insert(around.begin(), around.end());
    }
    std::map<VertexId, std::vector<VertexId>> rings;  // before the edit
    for (VertexId v : offered) {
        if (tin.is_alive(v)) tin.neighbours(v, rings[v]);
    }
    const test::TinState before = test::capture(tin);
    const std::size_t n0 = tin.vertex_count();
    const std::size_t constrained_edges = tin.constrained_edge_count();
    const auto constraints = tin.constraints();
    const double v0 = tin.volume();
    const double brute0 = test::brute_force_volume(tin);
    EditReport report;
    const BulkRemoval out = remove_in_patches(tin, offered, &report, may_border);

    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
    EXPECT_TRUE(test::mesh_is_sound(tin));
    EXPECT_EQ(out.candidates, offered.size());
    std::size_t died = 0;
    std::size_t offered_alive = 0;
    const VertexArrays& was = before.snapshot.vertices;
    for (std::uint32_t i = 0; i < was.size(); ++i) {
        if (!was.alive[i]) continue;
        const VertexId v{i};
        if (!tin.is_alive(v)) {
            ++died;
            EXPECT_TRUE(offer.count(v)) << "removed vertex " << i << " was not offered";
            EXPECT_FALSE(protected_vertices.count(v))
                << "removed vertex " << i << " was on or next to a constraint, or on the border";
            if (may_border) {
                for (VertexId w : rings.at(v)) {
                    if (tin.is_alive(w)) {
                        EXPECT_TRUE(may_border(v, w)) << i << " went while " << w.value << " stays";
                    }
                }
            }
            continue;
        }
        offered_alive += offer.count(v);
        EXPECT_EQ(tin.position(v), was.position[i]);
        EXPECT_EQ(tin.height(v), was.height[i]) << "VolumePolicy::Report moves no height";
    }
    std::size_t offered_live_before = 0;
    for (VertexId v : offer)
        offered_live_before += (v.value < was.size() && was.alive[v.value]) ? 1 : 0;
    EXPECT_EQ(out.removed, died);
    EXPECT_EQ(out.removed + offered_alive, offered_live_before);
    EXPECT_EQ(tin.vertex_count(), n0 - died);
    EXPECT_EQ(report.vertices_removed, died);
    EXPECT_EQ(report.vertices_created, 0u);
    EXPECT_EQ(tin.constrained_edge_count(), constrained_edges);
    const auto after = tin.constraints();
    EXPECT_EQ(after.size(), constraints.size());
    for (std::size_t k = 0; k < std::min(after.size(), constraints.size()); ++k)
        EXPECT_EQ(after[k].vertices, constraints[k].vertices);
    const double dv = tin.volume() - v0;
    EXPECT_TRUE(test::close_rel(report.volume_change, dv, 1e-12, 1e-15 * std::abs(v0)))
        << report.volume_change << " vs " << dv;
    EXPECT_TRUE(test::close_rel(report.volume_change, test::brute_force_volume(tin) - brute0, 1e-9,
                                1e-15 * std::abs(v0)));
    if (died == 0) test::expect_snapshots_equal(before.snapshot, tin.snapshot());
    return out;
}

TEST(ClearPatches, DenseTerrainWithConstraints) {
    for (std::uint64_t seed : {601u, 602u}) {
        SCOPED_TRACE(seed);
        Tin tin = test::smooth_terrain(test::kUnitSquare, 20000, seed, test::bumpy_sand, 0.02);
        constrain(tin, {{0.45, 0.45}, {0.55, 0.47}, {0.52, 0.56}}, true, 1);  // a ring
        constrain(tin, {{0.3, 0.6}, {0.42, 0.66}}, false, 2);
        constrain(tin, {{0.35, 0.7}, {0.4, 0.58}}, false, 3);  // crosses the previous one
        constrain(tin, {{0.6, 0.3}, {0.66, 0.31}}, false, 4);
        ASSERT_TRUE(tin.check_valid().ok());
        // A big disc holding all the constraints, one at the border, a few dead ids and repeats.
        std::vector<VertexId> offered = in_disc(tin, {0.5, 0.5}, 0.22);
        const std::vector<VertexId> border = in_disc(tin, {0.0, 0.3}, 0.08);
        offered.insert(offered.end(), border.begin(), border.end());
        offered.push_back(offered[10]);
        offered.push_back(VertexId{tin.vertex_capacity() + 3});
        ASSERT_GT(offered.size(), 3000u);
        const BulkRemoval out = clear_and_check(tin, offered);
        EXPECT_GE(out.patches, 1u);
        EXPECT_GT(out.removed, 0u);
    }
}

TEST(ClearPatches, TwoDisjointDiscsAreTwoPatches) {
    Tin tin = Tin::random_points(test::kUnitSquare, 8000, 611, test::bumpy_sand);
    std::vector<VertexId> offered = test::grow_to_disc(tin, in_disc(tin, {0.3, 0.3}, 0.07));
    const std::vector<VertexId> second = test::grow_to_disc(tin, in_disc(tin, {0.7, 0.6}, 0.09));
    ASSERT_TRUE(test::region_is_disc(tin, offered));
    ASSERT_TRUE(test::region_is_disc(tin, second));
    const std::size_t first_size = offered.size();
    offered.insert(offered.end(), second.begin(), second.end());
    const BulkRemoval out = clear_and_check(tin, offered);
    EXPECT_EQ(out.patches, 2u);
    EXPECT_EQ(out.refused, 0u);
    EXPECT_EQ(out.removed, first_size + second.size());
}

TEST(ClearPatches, DropsTheNeighboursOfAConstrainedVertexAndRemovesTheRest) {
    // A constraint crossing the rim of the offered disc: what the drop rule keeps (its vertices
    // and their neighbours) reaches the outside, so the rest is still one disc.
    Tin tin = Tin::random_points(test::kUnitSquare, 8000, 621, test::bumpy_sand);
    constrain(tin, {{0.585, 0.5}, {0.64, 0.505}}, false, 1);
    const std::vector<VertexId> offered = test::grow_to_disc(tin, in_disc(tin, {0.5, 0.5}, 0.1));
    // As one patch it does not qualify (it holds a constraint).
    {
        const test::TinState before = test::capture(tin);
        EXPECT_FALSE(tin.remove_patch(offered));
        test::expect_snapshots_equal(before.snapshot, tin.snapshot());
    }
    std::set<VertexId> kept;  // the constrained vertices and their neighbours must stay
    for (VertexId v : offered) {
        if (tin.is_on_constraint(v)) {
            std::vector<VertexId> around;
            tin.neighbours(v, around);
            kept.insert(v);
            kept.insert(around.begin(), around.end());
        }
    }
    std::size_t kept_at_least = 0;
    for (VertexId v : offered)
        kept_at_least += kept.count(v);
    ASSERT_GT(kept_at_least, 0u);
    const BulkRemoval out = clear_and_check(tin, offered);
    EXPECT_GE(out.patches, 1u);
    EXPECT_EQ(out.refused, 0u);
    EXPECT_GT(out.removed, offered.size() * 8 / 10) << out.removed << " of " << offered.size();
    EXPECT_LE(out.removed, offered.size() - kept_at_least);
}

TEST(ClearPatches, RemovesMostOfASetAroundAnInteriorConstraint) {
    // The drop rule keeps the constrained vertices and their neighbours inside the set, so the
    // rest is a ring, which no single remove_patch takes: it has to go in pieces.
    for (std::uint64_t seed : {622u, 623u, 624u}) {
        SCOPED_TRACE(seed);
        Tin tin = Tin::random_points(test::kUnitSquare, 8000, seed, test::bumpy_sand);
        constrain(tin, {{0.49, 0.5}, {0.515, 0.505}}, false, 1);
        const std::vector<VertexId> offered =
            test::grow_to_disc(tin, in_disc(tin, {0.5, 0.5}, 0.1));
        const BulkRemoval out = clear_and_check(tin, offered);
        EXPECT_GE(out.patches, 2u);
        EXPECT_GT(out.removed, offered.size() * 8 / 10) << out.removed << " of " << offered.size();
    }
}

TEST(ClearPatches, MayBorderDecidesWhoStaysNextToTheSurvivors) {
    {  // Nobody may border anything that stays: nothing goes.
        Tin tin = Tin::random_points(test::kUnitSquare, 4000, 651, test::bumpy_sand);
        const std::vector<VertexId> offered = in_disc(tin, {0.5, 0.5}, 0.1);
        const BulkRemoval out =
            clear_and_check(tin, offered, [](VertexId, VertexId) { return false; });
        EXPECT_EQ(out.removed, 0u);
    }
    {  // Survivors left of x = 0.5 may not border a removed vertex.
        Tin tin = Tin::random_points(test::kUnitSquare, 4000, 652, test::bumpy_sand);
        const std::vector<VertexId> offered =
            test::grow_to_disc(tin, in_disc(tin, {0.5, 0.5}, 0.1));
        const Tin* t = &tin;
        const BulkRemoval out = clear_and_check(
            tin, offered, [t](VertexId, VertexId w) { return t->position(w).x > 0.5; });
        EXPECT_GT(out.removed, 0u);
        EXPECT_LT(out.removed, offered.size());
    }
    {  // Always allowed: the same as no rule.
        Tin a = Tin::random_points(test::kUnitSquare, 4000, 653, test::bumpy_sand);
        Tin b = Tin::random_points(test::kUnitSquare, 4000, 653, test::bumpy_sand);
        const std::vector<VertexId> offered = test::grow_to_disc(a, in_disc(a, {0.5, 0.5}, 0.1));
        const BulkRemoval with =
            clear_and_check(a, offered, [](VertexId, VertexId) { return true; });
        const BulkRemoval without = clear_and_check(b, offered);
        EXPECT_EQ(with.removed, without.removed);
        EXPECT_EQ(test::triangle_set(a), test::triangle_set(b));
    }
}

TEST(ClearPatches, IslandsAndAnnuliNeverBreakTheMesh) {
    // The set surrounds vertices it does not offer: whatever is removed, the checks hold.
    Tin tin = Tin::random_points(test::kUnitSquare, 8000, 631, test::bumpy_sand);
    const std::vector<VertexId> disc = test::grow_to_disc(tin, in_disc(tin, {0.5, 0.5}, 0.1));
    std::vector<VertexId> annulus;
    for (VertexId v : disc) {
        if (distance(tin.position(v), Vec2{0.5, 0.5}) > 0.03) annulus.push_back(v);
    }
    clear_and_check(tin, annulus);
    Tin other = Tin::random_points(test::kUnitSquare, 8000, 632, test::bumpy_sand);
    std::vector<VertexId> holed = test::grow_to_disc(other, in_disc(other, {0.5, 0.5}, 0.1));
    const auto nearest = std::min_element(holed.begin(), holed.end(), [&](VertexId a, VertexId b) {
        return distance(other.position(a), Vec2{0.5, 0.5}) <
               distance(other.position(b), Vec2{0.5, 0.5});
    });
    holed.erase(nearest);
    clear_and_check(other, holed);
}

TEST(ClearPatches, NothingToDo) {
    Tin tin = Tin::random_points(test::kUnitSquare, 2000, 641, test::bumpy_sand);
    EXPECT_EQ(clear_and_check(tin, {}).removed, 0u);
    // Only border vertices.
    std::vector<VertexId> border;
    for (VertexId v : live_ids(tin)) {
        if (tin.is_boundary(v)) border.push_back(v);
    }
    const BulkRemoval out = clear_and_check(tin, border);
    EXPECT_EQ(out.removed, 0u);
    EXPECT_EQ(out.patches, 0u);
}

// ---- The drop rule against a brute-force fixed point -------------------------------------

using MayBorder = std::function<bool(VertexId v, VertexId w)>;

/// The set the drop rule leaves, by its definition: start from the offered live vertices
/// that are neither on the border nor on a constraint; then, over and over, mark every vertex
/// of the set that has a neighbour w outside it which is on a constraint, or is an island
/// (not on the border, and of every two consecutive neighbours of w at least one is in the
/// set), or which `may_border` refuses; drop all marked at once; until a pass marks nothing.
/// Public Tin queries only. `passes` receives the number of passes that dropped something.
std::set<VertexId> reference_drop_rule(const Tin& tin, const std::vector<VertexId>& offered,
                                       const MayBorder& may_border, int* passes) {
    std::set<VertexId> set;
    std::vector<VertexId> ring;
    for (VertexId v : offered) {
        if (!tin.is_alive(v)) continue;
        const Tin::VertexStar star = tin.star(v, ring);
        if (!star.boundary && !star.constrained) set.insert(v);
    }
    *passes = 0;
    std::vector<VertexId> around;
    for (;;) {
        std::vector<VertexId> marked;
        for (VertexId v : set) {
            tin.neighbours(v, ring);
            for (VertexId w : ring) {
                if (set.count(w)) continue;
                const Tin::VertexStar star = tin.star(w, around);
                bool island = !star.boundary;
                for (std::size_t k = 0; island && k < around.size(); ++k) {
                    island = set.count(around[k]) || set.count(around[(k + 1) % around.size()]);
                }
                if (star.constrained || island || (may_border && !may_border(v, w))) {
                    marked.push_back(v);
                    break;
                }
            }
        }
        if (marked.empty()) return set;
        ++*passes;
        for (VertexId v : marked)
            set.erase(v);
    }
}

/// Runs remove_in_patches and compares the vertices that died with the reference set. When
/// no piece was refused, every vertex of the reference set must go and no other; a refused
/// piece stays, so then the dead are only a subset (the cases below are chosen so that
/// nothing is refused, and say so). Returns the reference's pass count.
int expect_removal_follows_the_rule(Tin& tin, const std::vector<VertexId>& offered,
                                    const MayBorder& may_border, bool expect_no_refusal) {
    int passes = 0;
    const std::set<VertexId> expected = reference_drop_rule(tin, offered, may_border, &passes);
    const std::vector<VertexId> alive_before = live_ids(tin);
    EditReport report;
    const BulkRemoval out = remove_in_patches(tin, offered, &report, may_border);
    const ValidationReport valid = tin.check_valid();
    EXPECT_TRUE(valid.ok()) << valid.summary();
    std::set<VertexId> died;
    for (VertexId v : alive_before) {
        if (!tin.is_alive(v)) died.insert(v);
    }
    EXPECT_EQ(out.removed, died.size());
    EXPECT_EQ(report.vertices_removed, died.size());
    if (expect_no_refusal) {
        EXPECT_EQ(out.refused, 0u);
    }
    std::size_t not_in_reference = 0;
    for (VertexId v : died)
        not_in_reference += expected.count(v) ? 0 : 1;
    EXPECT_EQ(not_in_reference, 0u) << "vertices removed that the drop rule keeps";
    if (out.refused == 0) {
        std::size_t missing = 0;
        for (VertexId v : expected)
            missing += died.count(v) ? 0 : 1;
        EXPECT_EQ(missing, 0u) << "vertices the drop rule lets go that stayed, of "
                               << expected.size() << " (passes " << passes << ")";
    }
    return passes;
}

/// Segments between fresh end points, each its own constraint (insert_constraints).
void constrain_segments(Tin& tin, const std::vector<std::array<Vec2, 2>>& segments) {
    std::vector<Vec2> pts;
    std::vector<double> hs;
    for (const auto& s : segments) {
        for (Vec2 p : s) {
            pts.push_back(p);
            hs.push_back(test::bumpy_sand(p));
        }
    }
    const std::vector<VertexId> ids = tin.insert_points(pts, hs);
    std::vector<std::array<VertexId, 2>> pairs;
    for (std::size_t k = 0; k + 1 < ids.size(); k += 2)
        pairs.push_back({ids[k], ids[k + 1]});
    tin.insert_constraints(pairs, 1);
}

/// Deterministic, asymmetric refusal of about one pair in `one_in`.
MayBorder hashed_refusal(std::uint32_t one_in) {
    return [one_in](VertexId v, VertexId w) {
        std::uint64_t h = (std::uint64_t{v.value} << 32 | w.value) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
        return h % one_in != 0;
    };
}

TEST(ClearPatches, DropRuleMatchesTheFixedPointOfFullPasses) {
    int most_passes = 0;
    for (std::uint64_t seed : {661u, 662u, 663u, 664u}) {
        SCOPED_TRACE(seed);
        std::mt19937_64 rng = test::test_rng(seed);
        std::uniform_real_distribution<double> u(0.3, 0.7);
        const Vec2 c{u(rng), u(rng)};
        {  // A disc with a constraint through it and one just outside.
            Tin tin = Tin::random_points(test::kUnitSquare, 5000, seed, test::bumpy_sand);
            constrain_segments(tin, {{Vec2{c.x - 0.05, c.y - 0.02}, Vec2{c.x + 0.2, c.y + 0.03}},
                                     {Vec2{c.x - 0.1, c.y + 0.14}, Vec2{c.x + 0.1, c.y + 0.15}}});
            const std::vector<VertexId> offered = in_disc(tin, c, 0.13);
            most_passes =
                std::max(most_passes, expect_removal_follows_the_rule(tin, offered, nullptr, true));
        }
        {  // A blob of three discs, pairs refused by a hash.
            Tin tin = Tin::random_points(test::kUnitSquare, 5000, seed + 10, test::bumpy_sand);
            std::vector<VertexId> offered = in_disc(tin, c, 0.08);
            for (const Vec2 d : {Vec2{0.07, 0.02}, Vec2{-0.03, 0.08}}) {
                const std::vector<VertexId> more = in_disc(tin, c + d, 0.06);
                offered.insert(offered.end(), more.begin(), more.end());
            }
            most_passes = std::max(most_passes, expect_removal_follows_the_rule(
                                                    tin, offered, hashed_refusal(9), true));
        }
        {  // A disc that may not border survivors across a line through it.
            Tin tin = Tin::random_points(test::kUnitSquare, 5000, seed + 20, test::bumpy_sand);
            const Tin* t = &tin;
            const double cut = c.x + 0.3 * c.y;
            const MayBorder same_side = [t, cut](VertexId v, VertexId w) {
                const Vec2 a = t->position(v);
                const Vec2 b = t->position(w);
                return (a.x + 0.3 * a.y < cut) == (b.x + 0.3 * b.y < cut);
            };
            const std::vector<VertexId> offered = in_disc(tin, c, 0.12);
            most_passes = std::max(most_passes,
                                   expect_removal_follows_the_rule(tin, offered, same_side, true));
        }
        {  // Holes: the disc minus small discs, one around a single vertex, plus a constraint
           // near the rim and refusals.
            Tin tin = Tin::random_points(test::kUnitSquare, 5000, seed + 30, test::bumpy_sand);
            constrain_segments(tin, {{Vec2{c.x + 0.11, c.y - 0.05}, Vec2{c.x + 0.13, c.y + 0.06}}});
            const std::vector<VertexId> disc = in_disc(tin, c, 0.12);
            const VertexId centre =
                *std::min_element(disc.begin(), disc.end(), [&](auto a, auto b) {
                    return distance(tin.position(a), c) < distance(tin.position(b), c);
                });
            std::vector<VertexId> offered;
            for (VertexId v : disc) {
                const Vec2 p = tin.position(v);
                if (v == centre || distance(p, c + Vec2{0.05, 0.04}) < 0.025) continue;
                offered.push_back(v);
            }
            most_passes = std::max(most_passes, expect_removal_follows_the_rule(
                                                    tin, offered, hashed_refusal(23), true));
        }
    }
    // The cases must exercise the later passes, where the worklist replaces the full passes.
    EXPECT_GE(most_passes, 3);
}

}  // namespace
}  // namespace sandtin
