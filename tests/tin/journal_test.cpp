// The change journal: take_changes() against a brute-force diff of two snapshots, id and slot
// recycling, counts, and the range helpers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <set>
#include <vector>

#include "support/random_edits.hpp"
#include "support/tin_oracles.hpp"
#include "tin/change_journal.hpp"
#include "tin/tin.hpp"
#include "util/visit_marks.hpp"

namespace sandtin {
namespace {

using test::capture;
using test::changed_slots;
using test::changed_vertices;
using test::expand_ranges;
using test::list;

double dunes(Vec2 p) {
    return 2.0 + 0.4 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y);
}

void expect_counts(const Tin& tin, const ChangeSet& cs) {
    EXPECT_EQ(cs.vertex_capacity, tin.vertex_capacity());
    EXPECT_EQ(cs.slot_capacity, tin.slot_capacity());
    EXPECT_EQ(cs.live_vertices, tin.vertex_count());
    EXPECT_EQ(cs.live_slots, tin.triangle_count());
    EXPECT_EQ(cs.dead_slots, cs.slot_capacity - cs.live_slots);
    // Independently: count finite triangles slot by slot.
    std::uint32_t live = 0;
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s)
        live += tin.slot_triangle(s)[0].valid() ? 1 : 0;
    EXPECT_EQ(cs.live_slots, live);
}

TEST(Journal, FirstTakeChangesReportsEverything) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 500, 1, dunes);
    const ChangeSet cs = tin.take_changes();
    std::vector<std::uint32_t> all_vertices(tin.vertex_count());
    for (std::uint32_t i = 0; i < all_vertices.size(); ++i)
        all_vertices[i] = i;
    EXPECT_EQ(expand_ranges(cs.vertices), all_vertices);
    ASSERT_EQ(cs.vertices.size(), 1u);
    EXPECT_EQ(cs.vertices[0], (IdRange{0, 504}));
    ASSERT_EQ(cs.triangles.size(), 1u);
    EXPECT_EQ(cs.triangles[0], (IdRange{0, tin.slot_capacity()}));
    expect_counts(tin, cs);
    EXPECT_EQ(cs.live_vertices, 504u);
    EXPECT_EQ(cs.live_slots, 2u * 500u + 2u);
    // The dead slots of a fresh terrain are the faces outside the domain: one per hull edge,
    // and every hull vertex lies on the border.
    EXPECT_EQ(cs.dead_slots, test::border_vertex_count(tin));
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(Journal, FirstTakeChangesAfterRestoreReportsEverything) {
    Tin original = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 2, dunes);
    original.take_changes();
    for (VertexId v : test::live_ids(original)) {
        if (v.value % 3 == 0 && !original.is_boundary(v)) original.remove_vertex(v);
    }
    Tin tin = Tin::from_snapshot(original.snapshot());
    const ChangeSet cs = tin.take_changes();
    const std::vector<std::uint32_t> reported = expand_ranges(cs.vertices);
    const std::set<std::uint32_t> reported_set(reported.begin(), reported.end());
    for (VertexId v : test::live_ids(tin))
        EXPECT_TRUE(reported_set.count(v.value)) << v.value;
    const std::vector<std::uint32_t> slots = expand_ranges(cs.triangles);
    const std::set<std::uint32_t> slot_set(slots.begin(), slots.end());
    for (TriangleSlot s = 0; s < tin.slot_capacity(); ++s) {
        if (tin.slot_triangle(s)[0].valid()) {
            EXPECT_TRUE(slot_set.count(s)) << s;
        }
    }
    expect_counts(tin, cs);
    // Reported as a whole, holes included, as a reader opened on a terrain with holes is told
    // (the restore marks no id by id): one range each.
    EXPECT_EQ(cs.vertices, (std::vector<IdRange>{{0, tin.vertex_capacity()}}));
    EXPECT_EQ(cs.triangles, (std::vector<IdRange>{{0, tin.slot_capacity()}}));
    EXPECT_LT(tin.vertex_count(), tin.vertex_capacity());  // the removals left holes
    EXPECT_TRUE(tin.take_changes().empty());
}

TEST(Journal, IdleTinReportsNothing) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 100, 3, dunes);
    tin.take_changes();
    // Queries, no-op edits and refused edits change nothing.
    LocateHint hint;
    std::vector<VertexId> ns;
    for (VertexId v : test::live_ids(tin)) {
        (void)tin.locate(tin.position(v), &hint);
        (void)tin.height_at(tin.position(v) * 0.5, &hint);
        tin.neighbours(v, ns);
        tin.set_height(v, tin.height(v));
        tin.set_moisture(v, tin.vertices().moisture[v.index()]);
        if (tin.is_boundary(v)) {
            EXPECT_FALSE(tin.remove_vertex(v));
        }
    }
    (void)tin.volume();
    (void)tin.check_valid();
    (void)tin.snapshot();
    (void)tin.triangles();
    ReleaseFilter f;
    f.generation = 3;
    EXPECT_EQ(tin.release_constraints(f), 0u);
    const ChangeSet cs = tin.take_changes();
    EXPECT_TRUE(cs.empty()) << list(expand_ranges(cs.vertices)) << " "
                            << list(expand_ranges(cs.triangles));
    EXPECT_TRUE(cs.vertices.empty());
    EXPECT_TRUE(cs.triangles.empty());
    expect_counts(tin, cs);
}

TEST(Journal, AttributeSettersAreJournaled) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 100, 4, dunes);
    tin.take_changes();
    tin.set_height(VertexId{10}, 5.0);
    tin.set_material(VertexId{20}, 3);
    tin.set_moisture(VertexId{21}, 0.75f);
    tin.set_slide(VertexId{40}, {0.5f, 0.25f});
    tin.set_bedrock(VertexId{41}, -10.0);
    tin.set_water_depth(VertexId{60}, 0.125);
    ChangeSet cs = tin.take_changes();
    EXPECT_EQ(expand_ranges(cs.vertices), (std::vector<std::uint32_t>{10, 20, 21, 40, 41, 60}));
    EXPECT_EQ(cs.vertices, (std::vector<IdRange>{{10, 11}, {20, 22}, {40, 42}, {60, 61}}));
    EXPECT_TRUE(cs.triangles.empty());
    EXPECT_EQ(tin.vertices().height[10], 5.0);
    EXPECT_EQ(tin.vertices().material[20], 3);
    EXPECT_EQ(tin.vertices().moisture[21], 0.75f);
    EXPECT_EQ(tin.vertices().slide[40], (Vec2f{0.5f, 0.25f}));
    EXPECT_EQ(tin.vertices().bedrock[41], -10.0);
    EXPECT_EQ(tin.vertices().water_depth[60], 0.125);
    // Bad values and dead ids throw and journal nothing.
    EXPECT_THROW(tin.set_height(VertexId{10}, std::nan("")), std::invalid_argument);
    EXPECT_THROW(tin.set_moisture(VertexId{10}, 1.5f), std::invalid_argument);
    EXPECT_THROW(tin.set_moisture(VertexId{10}, -0.1f), std::invalid_argument);
    EXPECT_THROW(tin.set_slide(VertexId{10}, {std::nanf(""), 0.0f}), std::invalid_argument);
    EXPECT_THROW(tin.set_bedrock(VertexId{10}, std::nan("")), std::invalid_argument);
    EXPECT_THROW(tin.set_water_depth(VertexId{10}, -1e-9), std::invalid_argument);
    EXPECT_THROW(tin.set_water_depth(VertexId{10}, std::nan("")), std::invalid_argument);
    EXPECT_THROW(tin.set_water_depth(VertexId{100000}, 0.1), std::invalid_argument);
    EXPECT_THROW(tin.set_height(VertexId{100000}, 1.0), std::invalid_argument);
    EXPECT_THROW(tin.set_material(VertexId{}, 1), std::invalid_argument);
    cs = tin.take_changes();
    EXPECT_TRUE(cs.empty());
}

TEST(Journal, FreedIdsAndSlotsAreNotReusedBeforeTakeChanges) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 5, dunes);
    tin.take_changes();
    std::vector<VertexId> removed;
    for (VertexId v : test::live_ids(tin)) {
        if (removed.size() < 20 && !tin.is_boundary(v) && v.value % 4 == 1) {
            ASSERT_TRUE(tin.remove_vertex(v));
            removed.push_back(v);
        }
    }
    const TinSnapshot after_removal = tin.snapshot();
    std::set<TriangleSlot> freed;
    for (TriangleSlot s = 0; s < after_removal.slots.size(); ++s) {
        if (after_removal.slots[s][0] == kNoSlot) freed.insert(s);
    }
    ASSERT_FALSE(freed.empty());
    const std::uint32_t capacity = tin.vertex_capacity();
    std::mt19937_64 rng = test::test_rng(5);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    for (int i = 0; i < 40; ++i) {
        const VertexId v = tin.insert_point_on_surface({u(rng), u(rng)});
        EXPECT_EQ(std::find(removed.begin(), removed.end(), v), removed.end())
            << "id " << v.value << " reused before its death was reported";
        EXPECT_GE(v.value, capacity);
    }
    for (TriangleSlot s : freed) {
        EXPECT_FALSE(tin.slot_triangle(s)[0].valid())
            << "slot " << s << " reused before take_changes";
    }
    ChangeSet cs = tin.take_changes();
    expect_counts(tin, cs);
    // After the deaths are reported, the freed ids are handed out again (before new ones).
    const std::uint32_t capacity_now = tin.vertex_capacity();
    const std::uint32_t slots_now = tin.slot_capacity();
    std::set<VertexId> reused;
    for (std::size_t i = 0; i < removed.size(); ++i)
        reused.insert(tin.insert_point_on_surface({u(rng), u(rng)}));
    EXPECT_EQ(reused, std::set<VertexId>(removed.begin(), removed.end()));
    EXPECT_EQ(tin.vertex_capacity(), capacity_now);
    EXPECT_EQ(tin.slot_capacity(), slots_now) << "freed slots should be reused";
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(Journal, WithoutTrackingIdsAreRecycledAtOnce) {
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 100, 6, dunes, options);
    EXPECT_FALSE(tin.tracks_changes());
    const VertexId v = tin.insert_point({1.5, 1.5}, 1.0);
    const std::uint32_t slots = tin.slot_capacity();
    ASSERT_TRUE(tin.remove_vertex(v));
    const VertexId w = tin.insert_point({2.5, 2.5}, 1.0);
    EXPECT_EQ(w, v);
    // Slots too: many insert/remove cycles do not grow the slot buffer (each cycle kills at
    // least three faces, which without recycling would add as many new slots).
    for (int i = 0; i < 200; ++i) {
        const VertexId x = tin.insert_point({0.5 + 0.01 * i, 3.1}, 1.0);
        ASSERT_TRUE(tin.remove_vertex(x));
    }
    EXPECT_LE(tin.slot_capacity(), slots + 20);
    EXPECT_LE(tin.vertex_capacity(), 106u);
    const ChangeSet cs = tin.take_changes();
    EXPECT_TRUE(cs.empty());
    expect_counts(tin, cs);
    EXPECT_TRUE(tin.check_valid().ok());
}

/// Ids in `a` but not in `b` (both sorted).
std::vector<std::uint32_t> minus(const std::vector<std::uint32_t>& a,
                                 const std::vector<std::uint32_t>& b) {
    std::vector<std::uint32_t> out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

/// Runs random edits, taking changes every `batch` steps, and compares each ChangeSet with a
/// brute-force diff of the states before and after. Nothing that changed may be missing from
/// the journal. When the batch is one single edit call, nothing else may be reported either;
/// over longer batches an id may legitimately be reported after changing and changing back.
void run_journal_diff(std::uint64_t seed, int ops, int batch) {
    Tin tin = Tin::random_points(Rect::from_size(6.0, 6.0), 250, seed, dunes);
    tin.take_changes();
    test::RandomEditor editor(tin, seed, {.attribute_edits = true, .long_constraint = 0.03});
    test::TinState before = capture(tin);
    int missed = 0;
    int extra = 0;
    int exact_batches = 0;
    bool single = true;
    for (int op = 1; op <= ops; ++op) {
        const test::StepResult s = editor.step();
        single = single && s.single_edit;
        if (op % batch != 0) {
            single = false;
            continue;
        }
        const ChangeSet cs = tin.take_changes();
        const test::TinState after = capture(tin);
        const std::vector<std::uint32_t> want_v = changed_vertices(before, after);
        const std::vector<std::uint32_t> want_s = changed_slots(before, after);
        const std::vector<std::uint32_t> got_v = expand_ranges(cs.vertices);
        const std::vector<std::uint32_t> got_s = expand_ranges(cs.triangles);
        expect_counts(tin, cs);
        const auto missed_v = minus(want_v, got_v);
        const auto missed_s = minus(want_s, got_s);
        if (!missed_v.empty() || !missed_s.empty()) {
            if (++missed <= 5) {
                ADD_FAILURE() << "seed " << seed << " op " << op << " (" << s.name
                              << "): changes missing from the journal\n"
                              << "  vertices changed but not reported " << list(missed_v) << "\n"
                              << "  slots changed but not reported    " << list(missed_s);
            }
        }
        if (single) {
            ++exact_batches;
            const auto extra_v = minus(got_v, want_v);
            const auto extra_s = minus(got_s, want_s);
            if (!extra_v.empty() || !extra_s.empty()) {
                if (++extra <= 5) {
                    ADD_FAILURE() << "seed " << seed << " op " << op << " (" << s.name
                                  << ", one edit, reported volume change " << s.report.volume_change
                                  << "): journal reports unchanged items\n"
                                  << "  vertices reported but unchanged " << list(extra_v) << "\n"
                                  << "  slots reported but unchanged    " << list(extra_s);
                }
            }
        }
        before = after;
        single = true;
    }
    EXPECT_EQ(missed, 0) << "batches whose journal missed changes";
    EXPECT_EQ(extra, 0) << "single-edit batches whose journal reported unchanged items (of "
                        << exact_batches << ")";
    if (batch == 1) {
        EXPECT_GT(exact_batches, ops / 2);
    }
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(Journal, ExactlyTheChangesOfEachEdit) {
    run_journal_diff(11, 1200, 1);
}
TEST(Journal, ExactlyTheChangesOfEachEditSecondSeed) {
    run_journal_diff(12, 1200, 1);
}
TEST(Journal, EveryChangeOfMultiEditBatchesIsReported) {
    run_journal_diff(13, 1500, 9);
}

// ---- merge_into_ranges / count_in_ranges / DirtySet -------------------------------------

TEST(Ranges, MergeSimpleCases) {
    EXPECT_TRUE(merge_into_ranges({}).empty());
    EXPECT_EQ(merge_into_ranges({5}), (std::vector<IdRange>{{5, 6}}));
    EXPECT_EQ(merge_into_ranges({3, 1, 2, 2, 7, 9, 8, 3}), (std::vector<IdRange>{{1, 4}, {7, 10}}));
    EXPECT_EQ(merge_into_ranges({0, 2, 4}), (std::vector<IdRange>{{0, 1}, {2, 3}, {4, 5}}));
    // max_gap = number of clean ids a merged range may bridge.
    EXPECT_EQ(merge_into_ranges({0, 2, 4}, 1), (std::vector<IdRange>{{0, 5}}));
    EXPECT_EQ(merge_into_ranges({0, 3, 4}, 1), (std::vector<IdRange>{{0, 1}, {3, 5}}));
    EXPECT_EQ(merge_into_ranges({0, 3, 4}, 2), (std::vector<IdRange>{{0, 5}}));
    EXPECT_EQ(merge_into_ranges({0xFFFFFFF0u, 0xFFFFFFFDu}, 0),
              (std::vector<IdRange>{{0xFFFFFFF0u, 0xFFFFFFF1u}, {0xFFFFFFFDu, 0xFFFFFFFEu}}));
    EXPECT_EQ(count_in_ranges({}), 0u);
    EXPECT_EQ(count_in_ranges({{1, 4}, {7, 10}}), 6u);
    EXPECT_EQ(count_in_ranges({{0, 0xFFFFFFFEu}}), 0xFFFFFFFEull);
    EXPECT_EQ((IdRange{3, 8}).size(), 5u);
}

// Brute force: the ranges that cover `ids` when runs of at most `gap` uncovered ids between
// them are bridged, from a per-id scan.
std::vector<IdRange> bridged_by_scan(const std::vector<std::uint32_t>& ids, std::uint32_t gap) {
    if (ids.empty()) return {};
    const std::uint32_t top = *std::max_element(ids.begin(), ids.end()) + 1;
    std::vector<char> dirty(top, 0);
    for (std::uint32_t id : ids)
        dirty[id] = 1;
    std::vector<IdRange> out;
    std::uint32_t clean_run = 0;
    for (std::uint32_t id = 0; id < top; ++id) {
        if (!dirty[id]) {
            ++clean_run;
            continue;
        }
        if (!out.empty() && clean_run <= gap) {
            out.back().end = id + 1;
        } else {
            out.push_back({id, id + 1});
        }
        clean_run = 0;
    }
    return out;
}

// Coalescing exact ranges across gaps covers what a per-id scan bridging the same gaps covers.
TEST(Ranges, CoalescingExactRangesEqualsMergingTheIdsWithTheGap) {
    EXPECT_TRUE(coalesce_ranges({}, 5).empty());
    EXPECT_EQ(coalesce_ranges({{0, 2}, {4, 6}}, 1), (std::vector<IdRange>{{0, 2}, {4, 6}}));
    EXPECT_EQ(coalesce_ranges({{0, 2}, {4, 6}}, 2), (std::vector<IdRange>{{0, 6}}));
    EXPECT_EQ(coalesce_ranges({{0xFFFFFFF0u, 0xFFFFFFF1u}, {0xFFFFFFFDu, 0xFFFFFFFEu}}, 64),
              (std::vector<IdRange>{{0xFFFFFFF0u, 0xFFFFFFFEu}}));
    std::mt19937_64 rng = test::test_rng(37);
    for (int trial = 0; trial < 500; ++trial) {
        const auto gap = static_cast<std::uint32_t>(rng() % 70);
        const std::uint32_t universe = 1 + static_cast<std::uint32_t>(rng() % 2000);
        std::vector<std::uint32_t> ids;
        const std::size_t n = rng() % 300;
        for (std::size_t i = 0; i < n; ++i)
            ids.push_back(static_cast<std::uint32_t>(rng() % universe));
        const std::vector<IdRange> exact = merge_into_ranges(ids, 0);
        ASSERT_EQ(coalesce_ranges(exact, gap), bridged_by_scan(ids, gap))
            << "trial " << trial << " gap " << gap;
        ASSERT_EQ(merge_into_ranges(ids, gap), bridged_by_scan(ids, gap))
            << "trial " << trial << " gap " << gap;
        // With a cap: at most that many ranges, covering every id, and no more extra ids than
        // the brute-force best (join the smallest gaps first).
        const std::size_t cap = 1 + rng() % 20;
        const std::vector<IdRange> capped = coalesce_ranges(exact, gap, cap);
        const std::vector<IdRange> loose = bridged_by_scan(ids, gap);
        ASSERT_LE(capped.size(), std::max<std::size_t>(cap, 1)) << "trial " << trial;
        ASSERT_EQ(capped.size(), std::min(loose.size(), cap)) << "trial " << trial;
        std::vector<std::uint64_t> gaps;
        for (std::size_t i = 1; i < loose.size(); ++i)
            gaps.push_back(std::uint64_t{loose[i].begin} - loose[i - 1].end);
        std::sort(gaps.begin(), gaps.end());
        std::uint64_t best = count_in_ranges(loose);
        for (std::size_t i = 0; i + cap < loose.size(); ++i)
            best += gaps[i];
        ASSERT_EQ(count_in_ranges(capped), best) << "trial " << trial;
        for (std::uint32_t id : ids) {
            ASSERT_TRUE(std::any_of(capped.begin(), capped.end(),
                                    [&](IdRange r) { return r.begin <= id && id < r.end; }))
                << "trial " << trial;
        }
    }
}

TEST(Ranges, MergeMatchesBruteForce) {
    std::mt19937_64 rng = test::test_rng(31);
    for (int trial = 0; trial < 500; ++trial) {
        const std::uint32_t gap = static_cast<std::uint32_t>(trial % 4);
        const std::uint32_t universe = 1 + static_cast<std::uint32_t>(rng() % 200);
        std::vector<std::uint32_t> ids;
        const std::size_t n = rng() % 80;
        for (std::size_t i = 0; i < n; ++i)
            ids.push_back(static_cast<std::uint32_t>(rng() % universe));
        const std::set<std::uint32_t> unique(ids.begin(), ids.end());
        const std::vector<IdRange> ranges = merge_into_ranges(ids, gap);
        // Brute force: mark covered ids.
        std::vector<int> covered(universe + 10, 0);
        for (std::size_t k = 0; k < ranges.size(); ++k) {
            const IdRange r = ranges[k];
            ASSERT_LT(r.begin, r.end);
            ASSERT_TRUE(unique.count(r.begin)) << "a range must start at a dirty id";
            ASSERT_TRUE(unique.count(r.end - 1)) << "a range must end at a dirty id";
            if (k > 0) {
                ASSERT_GT(r.begin, ranges[k - 1].end + gap) << "ranges closer than the gap";
            }
            // Inside a range, no run of clean ids is longer than the gap.
            std::uint32_t run = 0;
            for (std::uint32_t i = r.begin; i < r.end; ++i) {
                ++covered[i];
                run = unique.count(i) ? 0 : run + 1;
                ASSERT_LE(run, gap);
            }
        }
        for (std::uint32_t id : unique)
            ASSERT_EQ(covered[id], 1) << id;
        for (std::size_t i = 0; i < covered.size(); ++i)
            ASSERT_LE(covered[i], 1);
        if (gap == 0) {
            ASSERT_EQ(count_in_ranges(ranges), unique.size());
        }
    }
}

TEST(DirtySetTest, MarkContainsTake) {
    DirtySet s;
    EXPECT_TRUE(s.empty());
    EXPECT_FALSE(s.contains(0));
    EXPECT_FALSE(s.contains(1000000));
    for (std::uint32_t id : {5u, 3u, 5u, 1000u, 3u, 0u})
        s.mark(id);
    EXPECT_FALSE(s.empty());
    EXPECT_EQ(s.ids(), (std::vector<std::uint32_t>{5, 3, 1000, 0}));  // insertion order, no repeats
    EXPECT_TRUE(s.contains(1000));
    EXPECT_TRUE(s.contains(0));
    EXPECT_FALSE(s.contains(4));
    EXPECT_FALSE(s.contains(999));
    std::vector<std::uint32_t> taken = s.take();
    std::sort(taken.begin(), taken.end());
    EXPECT_EQ(taken, (std::vector<std::uint32_t>{0, 3, 5, 1000}));
    EXPECT_TRUE(s.empty());
    EXPECT_FALSE(s.contains(5));
    EXPECT_FALSE(s.contains(1000));
    s.mark(5);
    EXPECT_EQ(s.ids(), (std::vector<std::uint32_t>{5}));
    s.clear();
    EXPECT_TRUE(s.empty());
    EXPECT_TRUE(s.take().empty());
}

TEST(DirtySetTest, RandomAgainstStdSet) {
    std::mt19937_64 rng = test::test_rng(7);
    DirtySet s;
    std::set<std::uint32_t> model;
    for (int i = 0; i < 20000; ++i) {
        const auto id = static_cast<std::uint32_t>(rng() % 5000);
        if (rng() % 1000 == 0) {
            std::vector<std::uint32_t> got = s.take();
            std::sort(got.begin(), got.end());
            ASSERT_EQ(got, std::vector<std::uint32_t>(model.begin(), model.end()));
            model.clear();
        }
        s.mark(id);
        model.insert(id);
        ASSERT_TRUE(s.contains(id));
        ASSERT_EQ(s.ids().size(), model.size());
    }
}

TEST(VisitMarksTest, RandomAgainstStdSet) {
    // Marks against a std::set through many O(1) clears, with ids that make the marks grow
    // after some walks (grown entries must not look marked in the current walk).
    std::mt19937_64 rng = test::test_rng(11);
    VisitMarks marks;
    std::set<std::uint32_t> model;
    std::uint32_t range = 64;
    for (int i = 0; i < 50000; ++i) {
        if (rng() % 500 == 0) {
            marks.clear();
            model.clear();
            range = std::min<std::uint32_t>(range * 2, 1u << 20);
        }
        const auto id = static_cast<std::uint32_t>(rng() % range);
        const auto probe = static_cast<std::uint32_t>(rng() % (2 * range));
        ASSERT_EQ(marks.contains(probe), model.count(probe) == 1) << "probe " << probe;
        ASSERT_EQ(marks.insert(id), model.insert(id).second) << "id " << id;
        ASSERT_TRUE(marks.contains(id));
    }
    marks.clear();
    for (std::uint32_t id = 0; id < 2 * range; id += 97)
        EXPECT_FALSE(marks.contains(id)) << id;
    // Room reserved mid-walk holds no marks; the ones set before stay.
    marks.mark(7);
    marks.reserve_ids(8 * static_cast<std::size_t>(range));
    EXPECT_TRUE(marks.contains(7));
    for (std::uint32_t id = 2 * range; id < 8 * range; id += 101)
        EXPECT_FALSE(marks.contains(id)) << id;
}

}  // namespace
}  // namespace sandtin
