// The change journal's readers: each reader (ChangeReader, and the default one behind
// take_changes()) reports everything that changed since its own previous take, whatever the
// others took (oracle: a brute-force diff of the snapshots each reader last saw), and a dead id
// comes back only once every open reader has taken its death.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "support/random_edits.hpp"
#include "support/tin_oracles.hpp"
#include "tin/change_reader.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

using test::capture;
using test::expand_ranges;
using test::list;

double reader_hills(Vec2 p) {
    return 1.0 + 0.3 * std::sin(1.7 * p.x) * std::cos(1.1 * p.y);
}

std::vector<std::uint32_t> missing(const std::vector<std::uint32_t>& want,
                                   const std::vector<std::uint32_t>& got) {
    std::vector<std::uint32_t> out;
    std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(out));
    return out;
}

/// An interior vertex of `tin` that can be removed.
VertexId interior_vertex(const Tin& tin) {
    for (VertexId v : test::live_ids(tin))
        if (!tin.is_boundary(v)) return v;
    return VertexId{};
}

TEST(ChangeReader, EachReaderSeesEveryChangeSinceItsOwnLastTake) {
    for (std::uint64_t seed : {3u, 8u}) {
        Tin tin = Tin::random_points(Rect::from_size(5.0, 5.0), 300, seed, reader_hills,
                                     TinOptions{.track_changes = false});
        // Readers that take at different paces: each must see what happened between its own
        // takes, even when another reader took (and ids were recycled) in between.
        constexpr int kPeriods[] = {1, 3, 7};
        std::vector<std::unique_ptr<ChangeReader>> readers;
        std::vector<test::TinState> seen;
        for (std::size_t r = 0; r < std::size(kPeriods); ++r) {
            readers.push_back(std::make_unique<ChangeReader>(tin));
            readers.back()->take();  // the first take reports everything
            seen.push_back(capture(tin));
        }
        test::RandomEditor editor(tin, seed, {.attribute_edits = true, .long_constraint = 0.03});
        int failures = 0;
        for (int op = 1; op <= 300; ++op) {
            (void)editor.step();
            for (std::size_t r = 0; r < readers.size(); ++r) {
                if (op % kPeriods[r] != 0) continue;
                const ChangeSet cs = readers[r]->take();
                const test::TinState now = capture(tin);
                const auto missed_v =
                    missing(test::changed_vertices(seen[r], now), expand_ranges(cs.vertices));
                const auto missed_s =
                    missing(test::changed_slots(seen[r], now), expand_ranges(cs.triangles));
                if ((!missed_v.empty() || !missed_s.empty()) && ++failures <= 3) {
                    ADD_FAILURE() << "seed " << seed << " op " << op << " reader " << r
                                  << ": vertices not reported " << list(missed_v)
                                  << ", slots not reported " << list(missed_s);
                }
                EXPECT_EQ(cs.vertex_capacity, tin.vertex_capacity());
                EXPECT_EQ(cs.slot_capacity, tin.slot_capacity());
                seen[r] = now;
            }
        }
        EXPECT_EQ(failures, 0);
        EXPECT_TRUE(tin.check_valid().ok());
    }
}

TEST(ChangeReader, ADeadIdComesBackOnlyOnceEveryOpenReaderHasTakenItsDeath) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 5, reader_hills,
                                 TinOptions{.track_changes = false});
    ChangeReader a(tin), b(tin);
    a.take();
    b.take();
    const VertexId dead = interior_vertex(tin);
    ASSERT_TRUE(dead.valid());
    ASSERT_TRUE(tin.remove_vertex(dead));
    // Neither reader has taken the death: a new vertex gets a fresh id.
    const VertexId first = tin.insert_point({1.01, 2.03}, 1.0);
    EXPECT_NE(first, dead);
    EXPECT_EQ(first.value, tin.vertex_capacity() - 1) << "a fresh id, past the old capacity";
    a.take();
    const VertexId second = tin.insert_point({2.02, 1.07}, 1.0);
    EXPECT_NE(second, dead) << "reader b has not yet seen the death";
    const ChangeSet seen_by_b = b.take();
    const std::vector<std::uint32_t> ids = expand_ranges(seen_by_b.vertices);
    EXPECT_TRUE(std::binary_search(ids.begin(), ids.end(), dead.value))
        << "b reports the death " << list(ids);
    // Now both have: the id is handed out again.
    const VertexId third = tin.insert_point({3.03, 3.01}, 1.0);
    EXPECT_EQ(third, dead);
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(ChangeReader, ClosingTheLastLaggingReaderLetsItsDeathsBeRecycled) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 6, reader_hills,
                                 TinOptions{.track_changes = false});
    ChangeReader a(tin);
    auto lagging = std::make_unique<ChangeReader>(tin);
    a.take();
    lagging->take();
    const VertexId dead = interior_vertex(tin);
    ASSERT_TRUE(tin.remove_vertex(dead));
    a.take();
    EXPECT_NE(tin.insert_point({1.01, 2.03}, 1.0), dead);
    lagging.reset();
    EXPECT_EQ(tin.insert_point({2.02, 1.07}, 1.0), dead);
}

// The editor holds recycling while a job reads the terrain on another thread: the frames'
// takes then leave the allocators as they are, and the first take after it lets go recycles.
TEST(ChangeReader, WhileRecyclingIsHeldATakenDeathStaysPendingUntilTheNextTakeAfter) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 8, reader_hills,
                                 TinOptions{.track_changes = false});
    ChangeReader a(tin);
    a.take();
    const VertexId dead = interior_vertex(tin);
    ASSERT_TRUE(tin.remove_vertex(dead));
    tin.hold_id_recycling(true);
    a.take();
    tin.hold_id_recycling(false);
    EXPECT_NE(tin.insert_point({1.01, 2.03}, 1.0), dead) << "not recycled by the held take";
    a.take();
    EXPECT_EQ(tin.insert_point({2.02, 1.07}, 1.0), dead) << "recycled by the take after it";
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(ChangeReader, WithoutReadersADeadIdIsRecycledAtOnce) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 7, reader_hills,
                                 TinOptions{.track_changes = false});
    const VertexId dead = interior_vertex(tin);
    ASSERT_TRUE(tin.remove_vertex(dead));
    EXPECT_EQ(tin.insert_point({1.01, 2.03}, 1.0), dead);
}

TEST(ChangeReader, AReaderOpenedLateReportsEverythingOnItsFirstTake) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 150, 9, reader_hills);
    tin.take_changes();
    tin.set_height(VertexId{12}, 2.0);
    ChangeReader late(tin);
    const ChangeSet first = late.take();
    ASSERT_EQ(first.vertices.size(), 1u);
    EXPECT_EQ(first.vertices[0], (IdRange{0, tin.vertex_capacity()}));
    ASSERT_EQ(first.triangles.size(), 1u);
    EXPECT_EQ(first.triangles[0], (IdRange{0, tin.slot_capacity()}));
    EXPECT_TRUE(late.take().empty());
}

TEST(ChangeReader, TheDefaultReaderAndOwnReadersDoNotTakeFromEachOther) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 150, 10, reader_hills);
    ChangeReader own(tin);
    tin.take_changes();
    own.take();
    tin.set_height(VertexId{20}, 2.5);
    EXPECT_EQ(tin.take_changes().vertices, (std::vector<IdRange>{{20, 21}}));
    EXPECT_EQ(own.take().vertices, (std::vector<IdRange>{{20, 21}}));
    tin.set_material(VertexId{30}, 2);
    EXPECT_EQ(own.take().vertices, (std::vector<IdRange>{{30, 31}}));
    EXPECT_EQ(tin.take_changes().vertices, (std::vector<IdRange>{{30, 31}}));
}

TEST(ChangeReader, TurningTheDefaultReaderOffReleasesTheDeathsItHeld) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 200, 11, reader_hills);
    tin.take_changes();
    const VertexId dead = interior_vertex(tin);
    ASSERT_TRUE(tin.remove_vertex(dead));
    EXPECT_NE(tin.insert_point({1.01, 2.03}, 1.0), dead);
    tin.set_track_changes(false);
    EXPECT_FALSE(tin.tracks_changes());
    EXPECT_TRUE(tin.take_changes().empty());  // counts, but no ranges
    EXPECT_EQ(tin.insert_point({2.02, 1.07}, 1.0), dead);
}

TEST(ChangeReader, TakingFromAReaderThatIsNotOpenIsAClearError) {
    Tin tin = Tin::random_points(Rect::from_size(4.0, 4.0), 50, 12, reader_hills);
    try {
        tin.take_changes(std::uint32_t{17});
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("not open"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sandtin
