// Half-edge pairing for restoring a triangulation from its triangles (engine/tin/detail).
// Oracle: a brute-force search over every pair of half-edges for the one running the other way;
// on closed soups each half-edge must have exactly one. Soups come from real terrains (random
// points, a cocircular grid) and from a fan whose centre has a thousand neighbours, so one
// vertex's row is long. Broken soups must be named: a duplicated or flipped triangle repeats
// an oriented edge, a missing triangle leaves an edge without twin, a corner beyond the vertex
// count is refused rather than read past the end.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "tin/detail/half_edge_twins.hpp"
#include "tin/tin.hpp"
#include "tin/tin_snapshot.hpp"

namespace sandtin {
namespace {

using Soup = std::vector<std::array<std::uint32_t, 3>>;
using detail::pair_half_edges;
using detail::TwinProblem;

std::uint32_t from(const Soup& s, std::size_t k) {
    return s[k / 3][(k % 3 + 1) % 3];
}
std::uint32_t to(const Soup& s, std::size_t k) {
    return s[k / 3][(k % 3 + 2) % 3];
}

/// Every half-edge's twin found by comparing it with every other half-edge; ~0u when there is
/// not exactly one.
std::vector<std::uint32_t> brute_force_twins(const Soup& s) {
    const std::size_t h = 3 * s.size();
    std::vector<std::uint32_t> twin(h, ~0u);
    for (std::size_t k = 0; k < h; ++k) {
        int found = 0;
        for (std::size_t j = 0; j < h; ++j) {
            if (from(s, j) == to(s, k) && to(s, j) == from(s, k)) {
                twin[k] = static_cast<std::uint32_t>(j);
                ++found;
            }
        }
        if (found != 1) twin[k] = ~0u;
    }
    return twin;
}

/// The triangles of a terrain, the vertex at infinity numbered after the last vertex id.
Soup soup_of(const Tin& tin, std::uint32_t& vertex_count) {
    const TinSnapshot snap = tin.snapshot();
    vertex_count = static_cast<std::uint32_t>(snap.vertices.size()) + 1;
    Soup soup;
    for (const auto& c : snap.slots) {
        if (c[0] == kNoSlot) continue;
        std::array<std::uint32_t, 3> t{};
        for (std::size_t i = 0; i < 3; ++i)
            t[i] = c[i] == kOutsideCorner ? vertex_count - 1 : c[i];
        soup.push_back(t);
    }
    return soup;
}

void expect_paired_like_brute_force(const Soup& soup, std::uint32_t vertex_count) {
    std::vector<std::uint32_t> twin;
    ASSERT_EQ(pair_half_edges(soup, vertex_count, twin), TwinProblem::None);
    const std::vector<std::uint32_t> expected = brute_force_twins(soup);
    ASSERT_EQ(twin.size(), expected.size());
    for (std::size_t k = 0; k < twin.size(); ++k) {
        ASSERT_NE(expected[k], ~0u) << "the soup is not closed at half-edge " << k;
        ASSERT_EQ(twin[k], expected[k]) << "half-edge " << k;
    }
}

TEST(HalfEdgeTwins, RandomTerrainMatchesBruteForce) {
    const Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 400, 7);
    std::uint32_t vertex_count = 0;
    const Soup soup = soup_of(tin, vertex_count);
    ASSERT_GT(soup.size(), 700u);
    expect_paired_like_brute_force(soup, vertex_count);
}

TEST(HalfEdgeTwins, CocircularGridMatchesBruteForce) {
    const Tin tin = Tin::regular_grid(Rect::from_size(4.0, 3.0), 12, 9);
    std::uint32_t vertex_count = 0;
    const Soup soup = soup_of(tin, vertex_count);
    expect_paired_like_brute_force(soup, vertex_count);
}

TEST(HalfEdgeTwins, LongRowsAroundAFanCentre) {
    // A convex 1000-gon fanned from its centre (vertex 0), closed by the vertex at infinity
    // (vertex 1001): both the centre and infinity have a thousand half-edges leaving them.
    constexpr std::uint32_t kRim = 1000;
    const std::uint32_t infinity = kRim + 1;
    Soup soup;
    for (std::uint32_t i = 0; i < kRim; ++i) {
        const std::uint32_t a = 1 + i, b = 1 + (i + 1) % kRim;
        soup.push_back({0, a, b});         // inside, counter-clockwise
        soup.push_back({b, a, infinity});  // outside: the rim edge the other way round
    }
    expect_paired_like_brute_force(soup, kRim + 2);
}

TEST(HalfEdgeTwins, EmptySoupHasNothingToPair) {
    std::vector<std::uint32_t> twin{1, 2, 3};
    EXPECT_EQ(pair_half_edges({}, 5, twin), TwinProblem::None);
    EXPECT_TRUE(twin.empty());
}

TEST(HalfEdgeTwins, BrokenSoupsAreNamed) {
    const Tin tin = Tin::random_points(Rect::from_size(10.0, 10.0), 60, 3);
    std::uint32_t vertex_count = 0;
    const Soup good = soup_of(tin, vertex_count);
    std::vector<std::uint32_t> twin;
    ASSERT_EQ(pair_half_edges(good, vertex_count, twin), TwinProblem::None);

    Soup duplicated = good;
    duplicated.push_back(good[5]);
    EXPECT_EQ(pair_half_edges(duplicated, vertex_count, twin), TwinProblem::RepeatedHalfEdge);

    Soup flipped = good;
    std::swap(flipped[5][0], flipped[5][1]);  // its edges now run like its neighbours' do
    EXPECT_EQ(pair_half_edges(flipped, vertex_count, twin), TwinProblem::RepeatedHalfEdge);

    Soup holed = good;
    holed.erase(holed.begin() + 5);
    EXPECT_EQ(pair_half_edges(holed, vertex_count, twin), TwinProblem::MissingTwin);

    EXPECT_EQ(pair_half_edges(good, vertex_count - 1, twin), TwinProblem::CornerOutOfRange)
        << "the vertex at infinity is numbered vertex_count - 1";
    EXPECT_EQ(pair_half_edges(good, 0, twin), TwinProblem::CornerOutOfRange);
}

}  // namespace
}  // namespace sandtin
