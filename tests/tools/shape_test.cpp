// Tool footprints: contours, normalisation, the outer offset, subdivision, interior seeds and
// lattices, clipping. Oracles: analytic circles and rectangles, brute-force simplicity and
// distance checks in extended precision, analytic clipped areas.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {
namespace {

using test::distance_to_border;
using test::inside_polygon;
using test::is_simple;
using test::signed_area_ld;

/// The λ of assets/tools/lambda.json, in metres (the test's own copy of the asset).
std::vector<Vec2> lambda_polygon() {
    const std::vector<Vec2> cm = {{4.5, -5.0},  {2.5, -5.0}, {0.0, 0.2},  {-2.6, -5.0},
                                  {-4.6, -5.0}, {-1.0, 1.5}, {-2.8, 5.0}, {-0.8, 5.0}};
    std::vector<Vec2> m;
    for (Vec2 p : cm)
        m.push_back(p * 0.01);
    return m;
}

std::vector<Vec2> reversed(std::vector<Vec2> v) {
    std::reverse(v.begin(), v.end());
    return v;
}

/// Same points, possibly starting elsewhere (cyclic rotation).
bool same_cycle(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t s = 0; s < a.size(); ++s) {
        bool all = true;
        for (std::size_t i = 0; i < a.size() && all; ++i)
            all = a[i] == b[(i + s) % b.size()];
        if (all) return true;
    }
    return false;
}

TEST(ToolShape, CircleContourIsARegularPolygonOnTheCircle) {
    for (int n : {3, 12, 64}) {
        const double r = 0.037;
        const std::vector<Vec2> c = circle_contour(r, n);
        ASSERT_EQ(c.size(), static_cast<std::size_t>(n));
        EXPECT_NEAR(c[0].x, r, 1e-17);
        EXPECT_NEAR(c[0].y, 0.0, 1e-17);
        for (int i = 0; i < n; ++i) {
            EXPECT_NEAR(length(c[static_cast<std::size_t>(i)]), r, 1e-16);
            const double angle =
                std::atan2(c[static_cast<std::size_t>(i)].y, c[static_cast<std::size_t>(i)].x);
            const double expected = 2.0 * std::numbers::pi * i / n;
            EXPECT_NEAR(std::remainder(angle - expected, 2.0 * std::numbers::pi), 0.0, 1e-12);
        }
        // Counter-clockwise, area of the regular n-gon.
        EXPECT_NEAR(static_cast<double>(signed_area_ld(c)),
                    0.5 * n * r * r * std::sin(2.0 * std::numbers::pi / n), 1e-15);
        EXPECT_TRUE(is_simple(c));
    }
    EXPECT_THROW(circle_contour(0.0, 12), std::invalid_argument);
    EXPECT_THROW(circle_contour(-1.0, 12), std::invalid_argument);
    EXPECT_THROW(circle_contour(std::nan(""), 12), std::invalid_argument);
    EXPECT_THROW(circle_contour(0.1, 2), std::invalid_argument);
}

TEST(ToolShape, RectangleContourSpansLengthAlongForwardAxis) {
    const std::vector<Vec2> r = rectangle_contour(0.06, 0.1);  // width across, length along +x
    ASSERT_EQ(r.size(), 4u);
    double minx = 1, maxx = -1, miny = 1, maxy = -1;
    for (Vec2 p : r) {
        minx = std::min(minx, p.x);
        maxx = std::max(maxx, p.x);
        miny = std::min(miny, p.y);
        maxy = std::max(maxy, p.y);
    }
    EXPECT_DOUBLE_EQ(maxx - minx, 0.1);
    EXPECT_DOUBLE_EQ(maxy - miny, 0.06);
    EXPECT_DOUBLE_EQ(minx + maxx, 0.0);
    EXPECT_DOUBLE_EQ(miny + maxy, 0.0);
    EXPECT_NEAR(static_cast<double>(signed_area_ld(r)), 0.006, 1e-16);  // counter-clockwise
    EXPECT_THROW(rectangle_contour(0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(rectangle_contour(1.0, -1.0), std::invalid_argument);
}

TEST(ToolShape, NormaliseContourRejectsNonSimpleAndOrientsCounterClockwise) {
    // A bow tie crosses itself.
    const std::vector<Vec2> bowtie = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    EXPECT_THROW(normalise_contour(bowtie), std::invalid_argument);
    // A polygon whose edges touch at a point (a figure eight through a shared vertex).
    const std::vector<Vec2> eight = {{0, 0}, {1, 0}, {1, 1}, {2, 1},
                                     {2, 2}, {1, 2}, {1, 1}, {0, 1}};
    EXPECT_THROW(normalise_contour(eight), std::invalid_argument);
    // Too few distinct points, zero area, non-finite.
    EXPECT_THROW(normalise_contour(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 0}}),
                 std::invalid_argument);
    EXPECT_THROW(normalise_contour(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}),
                 std::invalid_argument);
    EXPECT_THROW(normalise_contour(std::vector<Vec2>{{0, 0}, {1, 0}, {std::nan(""), 1}}),
                 std::invalid_argument);

    // Clockwise input comes back counter-clockwise with the same vertices.
    const std::vector<Vec2> ccw_square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    const std::vector<Vec2> cw = normalise_contour(reversed(ccw_square));
    EXPECT_GT(signed_area_ld(cw), 0.0L);
    EXPECT_TRUE(same_cycle(cw, ccw_square) || same_cycle(reversed(cw), reversed(ccw_square)));
    EXPECT_EQ(cw.size(), 4u);
    // Counter-clockwise input is kept as it is.
    EXPECT_TRUE(same_cycle(normalise_contour(ccw_square), ccw_square));
    // Repeated points and collinear points go; the closing duplicate too.
    const std::vector<Vec2> messy = {{0, 0}, {0, 0}, {1, 0}, {2, 0},
                                     {2, 2}, {2, 2}, {0, 2}, {0, 0}};
    const std::vector<Vec2> clean = normalise_contour(messy);
    EXPECT_TRUE(same_cycle(clean, ccw_square)) << clean.size() << " points";
    // The λ, in either orientation, is a valid non-convex contour, counter-clockwise.
    const std::vector<Vec2> raw = lambda_polygon();
    const std::vector<Vec2> ccw = signed_area_ld(raw) > 0.0L ? raw : reversed(raw);
    for (const auto& given : {raw, reversed(raw)}) {
        const std::vector<Vec2> lam = normalise_contour(given);
        EXPECT_EQ(lam.size(), 8u);
        EXPECT_GT(signed_area_ld(lam), 0.0L);
        EXPECT_TRUE(same_cycle(lam, ccw));
    }
}

/// The checks every tool shape must pass: O simple and counter-clockwise, I inside it with no
/// contact, the two borders at least the gap apart.
void expect_valid_shape(const ToolShape& s) {
    EXPECT_TRUE(is_simple(s.inner));
    EXPECT_TRUE(is_simple(s.outer)) << "outer contour is not simple";
    EXPECT_GT(signed_area_ld(s.inner), 0.0L);
    EXPECT_GT(signed_area_ld(s.outer), signed_area_ld(s.inner));
    EXPECT_GT(s.gap, 0.0);
    for (Vec2 p : s.inner)
        EXPECT_TRUE(inside_polygon(p, s.outer)) << p.x << ", " << p.y;
    for (std::size_t i = 0; i < s.inner.size(); ++i) {
        for (std::size_t j = 0; j < s.outer.size(); ++j) {
            EXPECT_FALSE(test::segments_touch(s.inner[i], s.inner[(i + 1) % s.inner.size()],
                                              s.outer[j], s.outer[(j + 1) % s.outer.size()]));
        }
    }
    // O is I offset outwards by the gap: never closer than that.
    EXPECT_GE(test::border_distance(s.inner, s.outer), s.gap * (1.0 - 1e-9));
    double far = 0.0;
    for (Vec2 p : s.outer)
        far = std::max(far, length(p));
    EXPECT_NEAR(s.bounding_radius, far, 1e-15);
}

TEST(ToolShape, ConvexOffsetKeepsEveryInnerVertexAtTheGap) {
    std::vector<std::vector<Vec2>> shapes = {circle_contour(0.04, 12),
                                             circle_contour(1.0, 40),
                                             rectangle_contour(0.06, 0.1),
                                             {{0, 0}, {0.05, -0.01}, {0.07, 0.03}, {0.01, 0.06}}};
    for (const auto& inner : shapes) {
        const double gap = 0.002;
        const ToolShape s = make_tool_shape(inner, gap);
        SCOPED_TRACE(std::to_string(inner.size()) + " vertices");
        EXPECT_DOUBLE_EQ(s.gap, gap);
        expect_valid_shape(s);
        // Convex corners are mitred: each inner vertex is exactly the gap from O.
        for (Vec2 p : s.inner)
            EXPECT_NEAR(distance_to_border(p, s.outer), gap, 1e-12 * std::max(1.0, length(p)));
        // And offset_contour alone gives the same outer contour.
        const std::vector<Vec2> o = offset_contour(s.inner, gap);
        EXPECT_EQ(o, s.outer);
    }
}

TEST(ToolShape, OffsetOfASquareIsTheMitredSquare) {
    const std::vector<Vec2> sq = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const std::vector<Vec2> o = offset_contour(sq, 0.25);
    ASSERT_EQ(o.size(), 4u);
    const std::vector<Vec2> expected = {{-1.25, -1.25}, {1.25, -1.25}, {1.25, 1.25}, {-1.25, 1.25}};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(o[i].x, expected[i].x, 1e-15);
        EXPECT_NEAR(o[i].y, expected[i].y, 1e-15);
    }
    // A needle-sharp corner is bevelled: O stays within 4 gaps of the corner.
    const std::vector<Vec2> needle = {{0, 0}, {1, 0.02}, {0, 0.04}};
    const std::vector<Vec2> on = offset_contour(normalise_contour(needle), 0.01);
    for (Vec2 p : on) {
        double nearest = 1e9;
        for (Vec2 q : needle)
            nearest = std::min(nearest, distance(p, q));
        EXPECT_LE(nearest, 4.0 * 0.01 * (1.0 + 1e-9));
    }
}

TEST(ToolShape, LambdaGivesAValidShape) {
    // The λ as the shipped asset builds it, and directly with several gaps (large gaps must
    // shrink until O is simple).
    const Tool tool = Tool::build(load_tool_asset("lambda"));
    expect_valid_shape(tool.shape());
    EXPECT_TRUE(same_cycle(tool.shape().inner, normalise_contour(lambda_polygon())));
    for (double gap : {0.0005, 0.002, 0.02, 0.2}) {
        SCOPED_TRACE(gap);
        const ToolShape s = make_tool_shape(lambda_polygon(), gap);
        EXPECT_LE(s.gap, gap);
        expect_valid_shape(s);
    }
    EXPECT_THROW(make_tool_shape(lambda_polygon(), 0.0), std::invalid_argument);
    EXPECT_THROW(make_tool_shape(lambda_polygon(), -1.0), std::invalid_argument);
}

TEST(ToolShape, SubdivideContourBoundsEdgeLengthAndKeepsTheVertices) {
    const std::vector<Vec2> lam = lambda_polygon();
    const double spacing = 0.007;
    const std::vector<Vec2> sub = subdivide_contour(lam, spacing);
    // Every original vertex is there, in order; every new point lies on its edge.
    std::size_t k = 0;
    for (std::size_t i = 0; i < sub.size(); ++i) {
        const Vec2 a = sub[i];
        const Vec2 b = sub[(i + 1) % sub.size()];
        EXPECT_LE(distance(a, b), spacing * (1.0 + 1e-12));
        EXPECT_GT(distance(a, b), 0.0);
        if (k < lam.size() && a == lam[k]) {
            ++k;
            continue;
        }
        const Vec2 from = lam[k - 1];
        const Vec2 to = lam[k % lam.size()];
        EXPECT_LE(test::distance_to_segment_ld(a, from, to), 1e-17);
    }
    EXPECT_EQ(k, lam.size());
    EXPECT_NEAR(static_cast<double>(signed_area_ld(sub)), static_cast<double>(signed_area_ld(lam)),
                1e-16);
}

TEST(ToolShape, InteriorSeedsAreStrictlyInside) {
    std::vector<std::vector<Vec2>> shapes = {
        circle_contour(0.04, 12), rectangle_contour(0.01, 3.0), normalise_contour(lambda_polygon()),
        subdivide_contour(normalise_contour(lambda_polygon()), 0.003)};
    for (const auto& poly : shapes) {
        const std::vector<Vec2> seeds = interior_seeds(poly);
        EXPECT_GE(seeds.size(), 1u);
        for (Vec2 s : seeds) {
            EXPECT_TRUE(inside_polygon(s, poly)) << s.x << ", " << s.y;
            EXPECT_GT(distance_to_border(s, poly), 0.0);
        }
    }
}

TEST(ToolShape, InteriorLatticeIsInsideClearOfTheBorderAndCoversTheInterior) {
    const std::vector<Vec2> lam = normalise_contour(lambda_polygon());
    for (double spacing : {0.004, 0.0025}) {
        const std::vector<Vec2> lattice = interior_lattice(lam, spacing);
        ASSERT_GT(lattice.size(), 20u);
        for (Vec2 p : lattice) {
            EXPECT_TRUE(inside_polygon(p, lam));
            EXPECT_GE(distance_to_border(p, lam), 0.5 * spacing * (1.0 - 1e-9));
        }
        // No two lattice points closer than the spacing (it is a lattice, not a cloud).
        for (std::size_t i = 0; i < lattice.size(); ++i) {
            for (std::size_t j = i + 1; j < lattice.size(); ++j)
                ASSERT_GE(distance(lattice[i], lattice[j]), spacing * (1.0 - 1e-9));
        }
        // Coverage: every point of the polygon deep inside has a lattice point within a
        // spacing (a triangular lattice covers the plane with radius spacing / sqrt(3)).
        for (Vec2 q : test::random_points_in(Rect{{-0.05, -0.05}, {0.05, 0.05}}, 3000, 9)) {
            if (!test::inside_by(q, lam, 1.5 * spacing)) continue;
            double nearest = 1e9;
            for (Vec2 p : lattice)
                nearest = std::min(nearest, distance(p, q));
            EXPECT_LE(nearest, spacing) << q.x << ", " << q.y;
        }
    }
    EXPECT_TRUE(interior_lattice(lam, 0.0).empty());
    EXPECT_TRUE(interior_lattice(lam, 1.0).empty());  // nothing fits
}

TEST(ToolShape, ClipToRectMatchesAnalyticIntersections) {
    const Vec2 lo{0.0, 0.0}, hi{2.0, 2.0};
    // A square straddling a corner: the overlap is the unit square.
    const std::vector<Vec2> sq = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const std::vector<Vec2> c1 = clip_to_rect(sq, lo, hi);
    EXPECT_NEAR(static_cast<double>(signed_area_ld(c1)), 1.0, 1e-15);
    // A diamond |x - 1| + |y - 1| <= 1.5 clipped to the square [0, 2]^2 loses four tips,
    // each a triangle of base 1 and height 0.5: area 2 * 1.5^2 - 4 * 0.25 = 3.5.
    const std::vector<Vec2> diamond = {{2.5, 1}, {1, 2.5}, {-0.5, 1}, {1, -0.5}};
    const std::vector<Vec2> c2 = clip_to_rect(diamond, lo, hi);
    EXPECT_NEAR(static_cast<double>(signed_area_ld(c2)), 3.5, 1e-14);
    EXPECT_EQ(c2.size(), 8u);
    // A disc (fine polygon) centred on the rectangle's edge: half of it.
    const std::vector<Vec2> disc = circle_contour(0.5, 400);
    std::vector<Vec2> moved;
    for (Vec2 p : disc)
        moved.push_back(p + Vec2{1.0, 0.0});
    const std::vector<Vec2> c3 = clip_to_rect(moved, lo, hi);
    EXPECT_NEAR(static_cast<double>(signed_area_ld(c3)),
                0.5 * static_cast<double>(signed_area_ld(moved)), 1e-12);
    for (const auto* c : {&c1, &c2, &c3}) {
        EXPECT_TRUE(is_simple(*c));
        for (Vec2 p : *c) {
            EXPECT_GE(p.x, lo.x);
            EXPECT_LE(p.x, hi.x);
            EXPECT_GE(p.y, lo.y);
            EXPECT_LE(p.y, hi.y);
        }
    }
    // Inside: unchanged. Outside: fewer than three points.
    const std::vector<Vec2> inside = {{0.5, 0.5}, {1.5, 0.5}, {1.0, 1.5}};
    EXPECT_EQ(clip_to_rect(inside, lo, hi), inside);
    const std::vector<Vec2> outside = {{3, 3}, {4, 3}, {4, 4}};
    EXPECT_LT(clip_to_rect(outside, lo, hi).size(), 3u);
}

TEST(ToolShape, SamplesAlongSidesCutOnlyTheEdgesOnTheRectanglesSides) {
    const Rect rect{{0.0, 0.0}, {2.0, 2.0}};
    // A disc centred on the left side, clipped: one edge lies on x = 0, the rest inside.
    std::vector<Vec2> disc;
    for (Vec2 p : circle_contour(0.7, 64))
        disc.push_back(p + Vec2{0.0, 1.0});
    const std::vector<Vec2> clipped = clip_to_rect(disc, rect.min, rect.max);
    const double spacing = 0.1;
    const std::vector<Vec2> samples = samples_along_sides(clipped, rect, spacing);
    // The edge on the side runs from y = 1 - 0.7 to 1 + 0.7 (the circle's top and bottom are
    // polygon vertices): 1.4 m in ceil(1.4 / 0.1) = 14 pieces, 13 inner points 0.1 m apart.
    ASSERT_EQ(samples.size(), 13u);
    std::vector<double> ys;
    for (Vec2 p : samples) {
        EXPECT_EQ(p.x, 0.0);  // exactly on the side
        ys.push_back(p.y);
    }
    std::sort(ys.begin(), ys.end());
    for (std::size_t k = 0; k < ys.size(); ++k)
        EXPECT_NEAR(ys[k], 0.3 + 1.4 * static_cast<double>(k + 1) / 14.0, 1e-14);
    // None repeats a vertex of the polygon.
    for (Vec2 p : samples)
        EXPECT_EQ(std::count(clipped.begin(), clipped.end(), p), 0);

    // A square inside touching no side, and a corner piece with two sides on the rectangle.
    const std::vector<Vec2> inside = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
    EXPECT_TRUE(samples_along_sides(inside, rect, spacing).empty());
    const std::vector<Vec2> corner = {{1.5, 1.5}, {2.0, 1.5}, {2.0, 2.0}, {1.5, 2.0}};
    const std::vector<Vec2> at_corner = samples_along_sides(corner, rect, 0.2);
    // Two sides 0.5 long, each in ceil(0.5 / 0.2) = 3 pieces: 2 inner points each.
    ASSERT_EQ(at_corner.size(), 4u);
    for (Vec2 p : at_corner)
        EXPECT_TRUE(p.x == 2.0 || p.y == 2.0);
    // Nothing without a positive spacing.
    EXPECT_TRUE(samples_along_sides(clipped, rect, 0.0).empty());
    EXPECT_TRUE(
        samples_along_sides(clipped, rect, std::numeric_limits<double>::quiet_NaN()).empty());
}

}  // namespace
}  // namespace sandtin
