// Polygon predicates. Oracles: hand-computed areas, shapes whose inside is known by
// construction, and brute-force sampling.

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "geom/polygon.hpp"
#include "geom/rect.hpp"
#include "geom/vec2.hpp"

namespace sandtin {
namespace {

// An L-shape (non-convex): the unit square [0,2]x[0,2] minus [1,2]x[1,2]. Area 3.
const std::vector<Vec2> kL = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

TEST(Polygon, SignedArea) {
    EXPECT_DOUBLE_EQ(signed_area(kL), 3.0);
    const std::vector<Vec2> cw(kL.rbegin(), kL.rend());
    EXPECT_DOUBLE_EQ(signed_area(cw), -3.0);
    const std::vector<Vec2> tri = {{1, 1}, {4, 1}, {1, 5}};
    EXPECT_DOUBLE_EQ(signed_area(tri), 6.0);
    EXPECT_EQ(signed_area(std::vector<Vec2>{{0, 0}, {1, 1}}), 0.0);
    EXPECT_EQ(signed_area(std::vector<Vec2>{}), 0.0);
    // Translation does not change the area; a regular n-gon approaches pi r^2.
    std::vector<Vec2> moved;
    for (Vec2 p : kL)
        moved.push_back(p + Vec2{100.0, -50.0});
    EXPECT_NEAR(signed_area(moved), 3.0, 1e-12);
    std::vector<Vec2> circle;
    const int n = 720;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        circle.push_back({2.0 * std::cos(a), 2.0 * std::sin(a)});
    }
    EXPECT_NEAR(signed_area(circle), 0.5 * n * 4.0 * std::sin(2.0 * std::numbers::pi / n), 1e-9);
}

TEST(Polygon, BoundingBox) {
    const Rect r = bounding_box(kL);
    EXPECT_EQ(r.min, (Vec2{0, 0}));
    EXPECT_EQ(r.max, (Vec2{2, 2}));
    EXPECT_TRUE(bounding_box(std::vector<Vec2>{}).empty());
}

TEST(Polygon, PointInNonConvexPolygon) {
    EXPECT_TRUE(point_in_polygon({0.5, 0.5}, kL));
    EXPECT_TRUE(point_in_polygon({1.5, 0.5}, kL));
    EXPECT_TRUE(point_in_polygon({0.5, 1.5}, kL));
    EXPECT_FALSE(point_in_polygon({1.5, 1.5}, kL));  // the notch
    EXPECT_FALSE(point_in_polygon({3.0, 0.5}, kL));
    EXPECT_FALSE(point_in_polygon({-0.1, 1.0}, kL));
    // Border points count as inside, including the reflex vertex and the notch edges.
    EXPECT_TRUE(point_in_polygon({1.0, 1.0}, kL));
    EXPECT_TRUE(point_in_polygon({1.5, 1.0}, kL));
    EXPECT_TRUE(point_in_polygon({1.0, 1.5}, kL));
    EXPECT_TRUE(point_in_polygon({0.0, 0.0}, kL));
    EXPECT_TRUE(point_in_polygon({2.0, 0.5}, kL));
    // Rays through vertices (y = 1 and y = 2 pass through corners).
    EXPECT_TRUE(point_in_polygon({0.5, 1.0}, kL));
    EXPECT_FALSE(point_in_polygon({-1.0, 1.0}, kL));
    EXPECT_FALSE(point_in_polygon({-1.0, 2.0}, kL));
    EXPECT_FALSE(point_in_polygon({-1.0, 0.0}, kL));
    EXPECT_FALSE(point_in_polygon({0.5, 0.5}, std::vector<Vec2>{{0, 0}, {1, 1}}));
    // Orientation does not matter.
    const std::vector<Vec2> cw(kL.rbegin(), kL.rend());
    EXPECT_FALSE(point_in_polygon({1.5, 1.5}, cw));
    EXPECT_TRUE(point_in_polygon({0.5, 1.5}, cw));
}

TEST(Polygon, PointInPolygonMatchesAnalyticStar) {
    // A five-pointed star (non-convex); inside by angular test against its radius function.
    std::vector<Vec2> star;
    for (int i = 0; i < 10; ++i) {
        const double a = std::numbers::pi / 2 + i * std::numbers::pi / 5;
        const double r = i % 2 == 0 ? 1.0 : 0.4;
        star.push_back({r * std::cos(a), r * std::sin(a)});
    }
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.1, 1.1);
    int inside = 0;
    for (int k = 0; k < 5000; ++k) {
        const Vec2 p{u(rng), u(rng)};
        // Brute force: p is inside iff it lies left of (or on) every edge of some triangle of
        // the fan from the centre (the star is star-shaped around the origin).
        bool expected = false;
        for (std::size_t i = 0; i < star.size(); ++i) {
            const Vec2 a = star[i];
            const Vec2 b = star[(i + 1) % star.size()];
            if (cross(a, p) >= -1e-15 && cross(b - a, p - a) >= -1e-15 && cross(p, b) >= -1e-15)
                expected = true;
        }
        EXPECT_EQ(point_in_polygon(p, star), expected) << p.x << "," << p.y;
        inside += expected ? 1 : 0;
    }
    EXPECT_GT(inside, 500);
}

TEST(Polygon, SegmentsIntersect) {
    // Proper crossing.
    EXPECT_TRUE(segments_intersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));
    // Disjoint, parallel, and disjoint with overlapping bounding boxes.
    EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {0, 1}, {1, 1}));
    EXPECT_FALSE(segments_intersect({0, 0}, {2, 2}, {3, 0}, {2, 0.5}));
    EXPECT_FALSE(segments_intersect({0, 0}, {1, 1}, {1.5, 0}, {0.6, 0.5}));
    // Touching endpoints, and an endpoint on the other segment's interior (T-junction).
    EXPECT_TRUE(segments_intersect({0, 0}, {1, 1}, {1, 1}, {2, 0}));
    EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {1, 5}));
    EXPECT_TRUE(segments_intersect({1, 5}, {1, 0}, {0, 0}, {2, 0}));
    // Collinear: overlapping, containing, touching at one point, and separate.
    EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));
    EXPECT_TRUE(segments_intersect({0, 0}, {4, 4}, {1, 1}, {2, 2}));
    EXPECT_TRUE(segments_intersect({0, 0}, {1, 0}, {1, 0}, {2, 0}));
    EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {1.5, 0}, {2, 0}));
    EXPECT_FALSE(segments_intersect({0, 0}, {1, 1}, {2, 2}, {3, 3}));
    // Degenerate segments (points).
    EXPECT_TRUE(segments_intersect({1, 1}, {1, 1}, {0, 0}, {2, 2}));
    EXPECT_FALSE(segments_intersect({1, 2}, {1, 2}, {0, 0}, {2, 2}));
    // Symmetric in its arguments.
    std::mt19937_64 rng(2);
    std::uniform_int_distribution<int> u(0, 4);
    auto lattice = [&] { return Vec2{static_cast<double>(u(rng)), static_cast<double>(u(rng))}; };
    for (int k = 0; k < 2000; ++k) {
        const Vec2 a = lattice(), b = lattice();
        const Vec2 c = lattice(), d = lattice();
        const bool r = segments_intersect(a, b, c, d);
        EXPECT_EQ(r, segments_intersect(b, a, c, d));
        EXPECT_EQ(r, segments_intersect(c, d, a, b));
        EXPECT_EQ(r, segments_intersect(a, b, d, c));
        // Brute force on the integer lattice: sample both segments densely in exact halves.
        bool sampled = false;
        for (int i = 0; i <= 48 && !sampled; ++i) {
            const Vec2 p = lerp(a, b, i / 48.0);
            if (distance_to_segment(p, c, d) < 1e-12) sampled = true;
        }
        for (int i = 0; i <= 48 && !sampled; ++i) {
            const Vec2 p = lerp(c, d, i / 48.0);
            if (distance_to_segment(p, a, b) < 1e-12) sampled = true;
        }
        if (sampled) {
            EXPECT_TRUE(r) << a.x << a.y << b.x << b.y << c.x << c.y << d.x << d.y;
        }
    }
}

TEST(Polygon, SegmentTouchesPolygon) {
    EXPECT_TRUE(segment_touches_polygon({0.2, 0.2}, {0.4, 0.4}, kL));   // inside
    EXPECT_TRUE(segment_touches_polygon({0.5, 0.5}, {5.0, 5.0}, kL));   // leaves
    EXPECT_TRUE(segment_touches_polygon({-1.0, 0.5}, {3.0, 0.5}, kL));  // crosses, ends outside
    EXPECT_TRUE(segment_touches_polygon({1.5, 1.5}, {1.5, 0.5}, kL));   // from the notch in
    EXPECT_TRUE(segment_touches_polygon({1.5, 1.5}, {1.5, 1.0}, kL));   // touches the notch edge
    EXPECT_FALSE(segment_touches_polygon({1.2, 1.2}, {1.8, 1.8}, kL));  // inside the notch
    EXPECT_FALSE(segment_touches_polygon({3.0, 0.0}, {3.0, 2.0}, kL));  // beside
    EXPECT_FALSE(segment_touches_polygon({1.2, 1.9}, {1.9, 1.2}, kL));  // across the notch only
    EXPECT_TRUE(
        segment_touches_polygon({2.0, 2.0}, {0.0, 3.0}, std::vector<Vec2>{{0, 0}, {2, 0}, {2, 2}}));
}

TEST(Polygon, IsSimplePolygon) {
    EXPECT_TRUE(is_simple_polygon(kL));
    EXPECT_TRUE(is_simple_polygon(std::vector<Vec2>(kL.rbegin(), kL.rend())));
    EXPECT_TRUE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
    // Bowtie: edges (0,0)-(2,2) and (2,0)-(0,2) cross.
    EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {2, 2}, {2, 0}, {0, 2}}));
    // Degenerate: too few vertices, zero area, repeated vertex, edge touching another edge.
    EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}}));
    EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}}));
    EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0}, {0, 1}}));
    EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));
}

TEST(Polygon, DistanceToSegment) {
    EXPECT_DOUBLE_EQ(distance_to_segment({0, 1}, {-1, 0}, {1, 0}), 1.0);
    EXPECT_DOUBLE_EQ(distance_to_segment({3, 4}, {0, 0}, {0, 0}), 5.0);
    EXPECT_DOUBLE_EQ(distance_to_segment({4, 4}, {0, 0}, {1, 0}), 5.0);
    EXPECT_DOUBLE_EQ(distance_to_segment({0.5, 0}, {0, 0}, {1, 0}), 0.0);
}

TEST(Polygon, NearestEdgeOfAClosedPolygon) {
    // The unit square, counter-clockwise: edge 3 is the closing one, from (0, 1) to (0, 0).
    const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const NearestEdge a = nearest_edge({0.25, -0.5}, square);
    EXPECT_EQ(a.index, 0u);
    EXPECT_DOUBLE_EQ(a.t, 0.25);
    EXPECT_DOUBLE_EQ(a.distance, 0.5);
    const NearestEdge b = nearest_edge({-2.0, 0.75}, square);
    EXPECT_EQ(b.index, 3u);
    EXPECT_DOUBLE_EQ(b.t, 0.25);  // from (0, 1) towards (0, 0)
    EXPECT_DOUBLE_EQ(b.distance, 2.0);
    // Against the brute force over distance_to_segment at scattered points.
    for (int k = 0; k < 50; ++k) {
        const Vec2 p{-1.0 + 0.061 * k, 2.0 - 0.077 * k};
        const NearestEdge e = nearest_edge(p, square);
        double best = 1e300;
        for (std::size_t i = 0; i < square.size(); ++i)
            best = std::min(best, distance_to_segment(p, square[i], square[(i + 1) % 4]));
        EXPECT_NEAR(e.distance, best, 1e-15);
        EXPECT_NEAR(distance_to_segment(p, square[e.index], square[(e.index + 1) % 4]), best,
                    1e-15);
    }
}

TEST(Polygon, PerimeterOfClosedPolygons) {
    const std::vector<Vec2> square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    EXPECT_DOUBLE_EQ(polygon_perimeter(square), 8.0);
    const std::vector<Vec2> triangle = {{0, 0}, {3, 0}, {3, 4}};  // 3-4-5
    EXPECT_DOUBLE_EQ(polygon_perimeter(triangle), 12.0);
    // A regular n-gon inscribed in the unit circle: 2 n sin(pi / n), towards 2 pi.
    std::vector<Vec2> ngon;
    for (int k = 0; k < 1000; ++k)
        ngon.push_back({std::cos(2.0 * std::numbers::pi * k / 1000),
                        std::sin(2.0 * std::numbers::pi * k / 1000)});
    EXPECT_NEAR(polygon_perimeter(ngon), 2000.0 * std::sin(std::numbers::pi / 1000), 1e-12);
    EXPECT_EQ(polygon_perimeter(std::vector<Vec2>{}), 0.0);
}

}  // namespace
}  // namespace sandtin
