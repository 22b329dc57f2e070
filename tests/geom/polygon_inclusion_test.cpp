// PolygonInclusion: point_in_polygon with two shortcuts around a centre. Its contract is to give
// the same answer as point_in_polygon for every point, so that is the oracle, applied to random
// points over the whole neighbourhood, to points straddling the two shortcut radii (measured
// here, in extended precision, from the polygon), and to points exactly on vertices and edges.
// A second, independent oracle (extended-precision crossing number away from the border) checks
// that the points sampled really exercise both answers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/polygon_inclusion.hpp"
#include "geom/rect.hpp"
#include "geom/vec2.hpp"
#include "support/tool_oracles.hpp"

namespace sandtin {
namespace {

const std::vector<Vec2> kLambda = test::unit_lambda();

struct Counts {
    std::size_t checked = 0;
    std::size_t inside = 0;   ///< clearly inside by the independent oracle
    std::size_t outside = 0;  ///< clearly outside by the independent oracle
};

/// Compares contains() with point_in_polygon() on every point; counts the clear answers.
void expect_same(const PolygonInclusion& inclusion, const std::vector<Vec2>& poly,
                 const std::vector<Vec2>& points, Counts& counts) {
    std::size_t mismatches = 0;
    for (const Vec2 p : points) {
        const bool expected = point_in_polygon(p, poly);
        if (inclusion.contains(p) != expected) {
            if (++mismatches <= 5) {
                ADD_FAILURE() << "point (" << p.x << ", " << p.y << "): point_in_polygon says "
                              << expected;
            }
        }
        ++counts.checked;
        counts.inside += test::inside_by(p, poly, 1e-9) ? 1 : 0;
        counts.outside += test::outside_by(p, poly, 1e-9) ? 1 : 0;
    }
    EXPECT_EQ(mismatches, 0u);
}

/// The two radii of the shortcuts, from the polygon in extended precision: the distance from
/// the centre to the nearest border point, and to the farthest vertex.
std::pair<double, double> radii(const std::vector<Vec2>& poly, Vec2 centre) {
    double reach = 0.0;
    for (const Vec2 v : poly)
        reach =
            std::max(reach, static_cast<double>(std::hypot(test::ld(v.x) - test::ld(centre.x),
                                                           test::ld(v.y) - test::ld(centre.y))));
    return {test::distance_to_border(centre, poly), reach};
}

/// Points at distances r (1 + s) from the centre in random directions, for relative offsets s of
/// both signs from 1e-9 to 1e-2 (log-uniform), around each of the two radii.
std::vector<Vec2> around_radii(const std::vector<Vec2>& poly, Vec2 centre, std::size_t count,
                               std::uint64_t seed) {
    const auto [clear, reach] = radii(poly, centre);
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_real_distribution<double> exponent(-9.0, -2.0);
    std::vector<Vec2> out;
    for (std::size_t k = 0; k < count; ++k) {
        const double r = (k % 2 == 0 ? clear : reach);
        const double s = ((k / 2) % 2 == 0 ? 1.0 : -1.0) * std::pow(10.0, exponent(rng));
        const double a = angle(rng);
        out.push_back(centre + Vec2{std::cos(a), std::sin(a)} * (r * (1.0 + s)));
    }
    return out;
}

/// Every vertex, and points at fractions k/8 along every edge (on the edge up to rounding).
std::vector<Vec2> on_border(const std::vector<Vec2>& poly) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[(i + 1) % poly.size()];
        for (int k = 0; k < 8; ++k)
            out.push_back(a + (b - a) * (k / 8.0));
    }
    return out;
}

/// 10^5 random points in the polygon's bounding box grown by half its size on each side, the
/// points around both radii, and the border points.
Counts check_everywhere(const std::vector<Vec2>& poly, Vec2 centre, std::uint64_t seed) {
    const PolygonInclusion inclusion(poly, centre);
    Counts counts;
    Rect box = bounding_box(poly);
    const Vec2 grow{box.width() * 0.5, box.height() * 0.5};
    box = Rect{box.min - grow, box.max + grow};
    expect_same(inclusion, poly, test::random_points_in(box, 100000, seed), counts);
    expect_same(inclusion, poly, around_radii(poly, centre, 20000, seed + 1), counts);
    Counts border;
    expect_same(inclusion, poly, on_border(poly), border);
    // Every border point counts as inside (point_in_polygon's documented rule).
    for (const Vec2 p : on_border(poly))
        EXPECT_TRUE(inclusion.contains(p)) << "(" << p.x << ", " << p.y << ")";
    return counts;
}

TEST(PolygonInclusion, CirclePolygonCentredInside) {
    const Vec2 c{0.5, 0.5};
    const auto poly = test::regular_polygon(c, 0.1, 64);
    const Counts n = check_everywhere(poly, c, 11);
    EXPECT_GT(n.inside, 5000u);
    EXPECT_GT(n.outside, 50000u);
    // Off-centre inside, and a polygon far from the origin (rounding scales with coordinates).
    check_everywhere(poly, {0.57, 0.46}, 12);
    const auto far = test::regular_polygon({1200.0, -800.0}, 0.25, 48);
    check_everywhere(far, {1200.1, -800.05}, 13);
}

TEST(PolygonInclusion, ConcavePolygon) {
    ASSERT_TRUE(test::is_simple(kLambda));
    ASSERT_GT(test::signed_area_ld(kLambda), 0.0L);
    // Centre inside the long stroke.
    const Counts n = check_everywhere(kLambda, {0.6, 0.5}, 21);
    EXPECT_GT(n.inside, 10000u);
    EXPECT_GT(n.outside, 50000u);
    // Centre inside the short leg, near the joint.
    check_everywhere(kLambda, {0.3, 0.3}, 22);
}

TEST(PolygonInclusion, CentreOutside) {
    // In the notch between the λ's legs: the clear disc is outside, the ring wraps the polygon.
    ASSERT_FALSE(test::inside_polygon({0.5, 0.1}, kLambda));
    const Counts n = check_everywhere(kLambda, {0.5, 0.1}, 31);
    EXPECT_GT(n.inside, 5000u);
    // Far away from the polygon: nearly everything is decided by the two radii.
    check_everywhere(kLambda, {3.0, -2.0}, 32);
    check_everywhere(test::regular_polygon({0.5, 0.5}, 0.1, 64), {0.5, 0.75}, 33);
}

TEST(PolygonInclusion, CentreOnTheBorder) {
    // On a vertex and on an edge: the clear disc is empty, so every answer is the full test's.
    check_everywhere(kLambda, kLambda[2], 41);
    check_everywhere(kLambda, (kLambda[4] + kLambda[5]) * 0.5, 42);
    const auto poly = test::regular_polygon({0.5, 0.5}, 0.1, 64);
    check_everywhere(poly, poly[7], 43);
}

TEST(PolygonInclusion, BorderToleranceSeenFromAnOutsideCentre) {
    // Within point_in_polygon's border band (about 1e-12 off an edge, counted as inside) but
    // nearer the outside centre than the edge is: the shortcut must not answer "outside".
    const std::vector<Vec2> diamond = {{1, 0}, {2, 1}, {1, 2}, {0, 1}};
    const PolygonInclusion inclusion(diamond, {0.0, 0.0});
    for (double e : {3e-13, 1e-12, 2e-12, 1e-11}) {
        const Vec2 p{0.5 - e, 0.5 - e};
        EXPECT_EQ(inclusion.contains(p), point_in_polygon(p, diamond)) << e;
    }
    // The same just beyond the farthest vertex, seen from far away.
    const PolygonInclusion far(diamond, {-10.0, 1.0});
    for (double e : {3e-13, 1e-12, 2e-12, 1e-11}) {
        const Vec2 p{2.0 + e, 1.0};
        EXPECT_EQ(far.contains(p), point_in_polygon(p, diamond)) << e;
    }
}

/// Each edge split into `parts` equal pieces, as the stamp subdivides a tool's contours.
std::vector<Vec2> subdivided(const std::vector<Vec2>& poly, int parts) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[(i + 1) % poly.size()];
        for (int k = 0; k < parts; ++k)
            out.push_back(a + (b - a) * (static_cast<double>(k) / parts));
    }
    return out;
}

/// Points on the horizontal line through every vertex, across the whole box (the crossing
/// number's classic edge case: the ray passes through a vertex).
std::vector<Vec2> through_vertices(const std::vector<Vec2>& poly, std::uint64_t seed) {
    const Rect box = bounding_box(poly);
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> x(box.min.x - 0.1, box.max.x + 0.1);
    std::vector<Vec2> out;
    for (const Vec2 v : poly) {
        for (int k = 0; k < 20; ++k)
            out.push_back({x(rng), v.y});
    }
    return out;
}

// Contours with more edges than the whole-polygon test is kept for go through the index of
// edges by height; the answers must stay point_in_polygon's, bit for bit.
TEST(PolygonInclusion, BandedLetterAndStarAgreeEverywhere) {
    const std::vector<Vec2> letter = subdivided(kLambda, 25);  // 200 edges
    ASSERT_TRUE(test::is_simple(letter));
    Counts n = check_everywhere(letter, {0.6, 0.5}, 51);
    EXPECT_GT(n.inside, 10000u);
    EXPECT_GT(n.outside, 50000u);
    check_everywhere(letter, {0.5, 0.1}, 52);  // centre in the notch
    check_everywhere(letter, letter[37], 53);  // centre on the border
    Counts lines;
    expect_same(PolygonInclusion(letter, {0.6, 0.5}), letter, through_vertices(letter, 54), lines);

    // A star of 150 spikes: a horizontal line meets many edges, and a band holds many.
    std::vector<Vec2> star;
    for (int k = 0; k < 300; ++k) {
        const double a = 2.0 * std::numbers::pi * k / 300;
        const double r = k % 2 == 0 ? 0.3 : 0.12;
        star.push_back({0.5 + r * std::cos(a), 0.5 + r * std::sin(a)});
    }
    n = check_everywhere(star, {0.5, 0.5}, 55);
    EXPECT_GT(n.inside, 5000u);
    expect_same(PolygonInclusion(star, {0.5, 0.5}), star, through_vertices(star, 56), lines);
}

TEST(PolygonInclusion, BandedCombWithHorizontalEdges) {
    // A comb: 20 teeth with horizontal tops and bottoms, each edge split in three, so whole
    // edges lie exactly on band heights; seen from a centre in the spine and one far outside.
    std::vector<Vec2> comb = {{0.0, 0.0}, {2.0, 0.0}};
    for (int t = 19; t >= 0; --t) {
        const double x = 0.1 * t;
        comb.push_back({x + 0.1, 0.2});
        comb.push_back({x + 0.1, 1.0});
        comb.push_back({x + 0.05, 1.0});
        comb.push_back({x + 0.05, 0.2});
    }
    comb.pop_back();
    comb.back() = {0.0, 1.0};
    const std::vector<Vec2> fine = subdivided(comb, 3);
    ASSERT_TRUE(test::is_simple(fine));
    const Counts n = check_everywhere(fine, {1.0, 0.1}, 61);
    EXPECT_GT(n.inside, 5000u);
    check_everywhere(fine, {5.0, 5.0}, 62);
    Counts lines;
    expect_same(PolygonInclusion(fine, {1.0, 0.1}), fine, through_vertices(fine, 63), lines);
    // Not finite: outside, as point_in_polygon says.
    const PolygonInclusion inclusion(fine, {1.0, 0.1});
    EXPECT_FALSE(inclusion.contains({0.5, std::nan("")}));
    EXPECT_FALSE(inclusion.contains({std::nan(""), 0.5}));
}

}  // namespace
}  // namespace sandtin
