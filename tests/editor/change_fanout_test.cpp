// The editor's journal fan-out: the union of range lists against a brute-force set union, and
// two channels that take at different times each receive every change exactly as a sole
// consumer of Tin::take_changes() would (oracle: the ids the test itself edited).

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "change_fanout.hpp"
#include "tin/tin.hpp"

namespace sandtin::editor {
namespace {

std::set<std::uint32_t> ids_of(const std::vector<IdRange>& ranges) {
    std::set<std::uint32_t> out;
    for (const IdRange r : ranges)
        for (std::uint32_t i = r.begin; i < r.end; ++i)
            out.insert(i);
    return out;
}

std::vector<IdRange> random_ranges(std::mt19937& rng) {
    std::vector<std::uint32_t> ids;
    std::uniform_int_distribution<std::uint32_t> id(0, 200);
    const int n = std::uniform_int_distribution<int>(0, 40)(rng);
    for (int i = 0; i < n; ++i)
        ids.push_back(id(rng));
    return merge_into_ranges(ids);
}

TEST(ChangeFanout, UnionOfRangesIsTheSetUnionSortedAndDisjoint) {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 500; ++trial) {
        const std::vector<IdRange> a = random_ranges(rng), b = random_ranges(rng);
        const std::vector<IdRange> u = union_of_ranges(a, b);
        std::set<std::uint32_t> want = ids_of(a);
        const std::set<std::uint32_t> bs = ids_of(b);
        want.insert(bs.begin(), bs.end());
        EXPECT_EQ(ids_of(u), want);
        for (std::size_t i = 1; i < u.size(); ++i)
            EXPECT_LT(u[i - 1].end, u[i].begin) << "ranges overlap or touch";
    }
}

TEST(ChangeFanout, EveryChannelSeesEveryChangeWheneverItTakes) {
    Tin tin = Tin::regular_grid({{0, 0}, {1, 1}}, 20, 20, [](Vec2) { return 0.0; });
    ChangeFanout fanout(tin);
    (void)fanout.take(ChangeFanout::Mesh);  // the first take reports everything
    (void)fanout.take(ChangeFanout::Mirror);
    EXPECT_TRUE(fanout.take(ChangeFanout::Mesh).empty());

    tin.set_height(VertexId{5}, 0.1);
    tin.set_height(VertexId{7}, 0.1);
    const ChangeSet mesh1 = fanout.take(ChangeFanout::Mesh);
    EXPECT_EQ(ids_of(mesh1.vertices), (std::set<std::uint32_t>{5, 7}));
    tin.set_height(VertexId{100}, 0.2);
    tin.set_height(VertexId{6}, 0.2);
    // The mirror had not taken yet: it gets both edits, merged.
    const ChangeSet mirror = fanout.take(ChangeFanout::Mirror);
    EXPECT_EQ(ids_of(mirror.vertices), (std::set<std::uint32_t>{5, 6, 7, 100}));
    EXPECT_EQ(mirror.vertices.size(), 2u) << "5, 6, 7 are one range";
    // The mesh gets only what came after its own take.
    const ChangeSet mesh2 = fanout.take(ChangeFanout::Mesh);
    EXPECT_EQ(ids_of(mesh2.vertices), (std::set<std::uint32_t>{6, 100}));
    EXPECT_EQ(mesh2.vertex_capacity, tin.vertices().size());
    // A re-triangulation: both channels see the same dirty slots.
    const VertexId v = tin.insert_point_on_surface({0.512, 0.487});
    ASSERT_TRUE(v.valid());
    const ChangeSet a = fanout.take(ChangeFanout::Mesh), b = fanout.take(ChangeFanout::Mirror);
    EXPECT_FALSE(a.triangles.empty());
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_TRUE(fanout.take(ChangeFanout::Mesh).empty());
    EXPECT_TRUE(fanout.take(ChangeFanout::Mirror).empty());
}

}  // namespace
}  // namespace sandtin::editor
