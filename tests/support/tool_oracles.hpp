#pragma once
// Independent oracles for the sculpting-tool tests: polygon predicates re-derived in extended
// precision (not geom/polygon.hpp, which the tools themselves use), terrains with analytic
// heights, dense sampling of the surface and the usual soundness check of a mesh.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

/// Crossing-number point-in-polygon in extended precision. Points on the border may go
/// either way; callers keep a margin from the border.
inline bool inside_polygon(Vec2 p, std::span<const Vec2> poly) {
    bool inside = false;
    const std::size_t n = poly.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[j];
        if ((a.y > p.y) != (b.y > p.y)) {
            const long double x =
                ld(a.x) + (ld(p.y) - ld(a.y)) * (ld(b.x) - ld(a.x)) / (ld(b.y) - ld(a.y));
            if (ld(p.x) < x) inside = !inside;
        }
    }
    return inside;
}

/// Distance from p to the border of the closed polygon.
inline double distance_to_border(Vec2 p, std::span<const Vec2> poly) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < poly.size(); ++i)
        best = std::min(best, distance_to_segment_ld(p, poly[i], poly[(i + 1) % poly.size()]));
    return best;
}

/// Inside the polygon and farther than `margin` from its border.
inline bool inside_by(Vec2 p, std::span<const Vec2> poly, double margin) {
    return inside_polygon(p, poly) && distance_to_border(p, poly) > margin;
}

/// Outside the polygon and farther than `margin` from its border.
inline bool outside_by(Vec2 p, std::span<const Vec2> poly, double margin) {
    return !inside_polygon(p, poly) && distance_to_border(p, poly) > margin;
}

inline long double signed_area_ld(std::span<const Vec2> poly) {
    long double s = 0.0L;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[(i + 1) % poly.size()];
        s += ld(a.x) * ld(b.y) - ld(b.x) * ld(a.y);
    }
    return s / 2.0L;
}

inline int sign_ld(long double v) {
    return v > 0.0L ? 1 : (v < 0.0L ? -1 : 0);
}

/// Closed segments [a,b] and [c,d] share a point (extended precision orientation tests).
inline bool segments_touch(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const int o1 = sign_ld(orient2(a, b, c));
    const int o2 = sign_ld(orient2(a, b, d));
    const int o3 = sign_ld(orient2(c, d, a));
    const int o4 = sign_ld(orient2(c, d, b));
    if (o1 != o2 && o3 != o4) return true;
    auto on = [](Vec2 p, Vec2 q, Vec2 r) {  // r on segment p-q, given collinear
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) &&
               std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
    };
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
           (o4 == 0 && on(c, d, b));
}

/// No two non-adjacent edges touch, adjacent edges meet only at their shared vertex, and the
/// area is non-zero: brute force over all edge pairs.
inline bool is_simple(std::span<const Vec2> poly) {
    const std::size_t n = poly.size();
    if (n < 3 || signed_area_ld(poly) == 0.0L) return false;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[(i + 1) % n];
        if (a == b) return false;
        for (std::size_t j = i + 1; j < n; ++j) {
            const Vec2 c = poly[j];
            const Vec2 d = poly[(j + 1) % n];
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if (adjacent) {
                // Overlapping adjacent edges (a spike) are not simple either.
                const Vec2 shared = j == i + 1 ? b : a;
                const Vec2 p = j == i + 1 ? a : b;
                const Vec2 q = j == i + 1 ? d : c;
                if (orient2(p, shared, q) == 0.0L &&
                    (ld(p.x) - ld(shared.x)) * (ld(q.x) - ld(shared.x)) +
                            (ld(p.y) - ld(shared.y)) * (ld(q.y) - ld(shared.y)) >
                        0.0L) {
                    return false;
                }
                continue;
            }
            if (segments_touch(a, b, c, d)) return false;
        }
    }
    return true;
}

/// Smallest distance between the borders of two polygons that do not cross.
inline double border_distance(std::span<const Vec2> p, std::span<const Vec2> q) {
    double best = std::numeric_limits<double>::infinity();
    for (Vec2 v : p)
        best = std::min(best, distance_to_border(v, q));
    for (Vec2 v : q)
        best = std::min(best, distance_to_border(v, p));
    return best;
}

/// A regular n-gon inscribed in the circle of `radius` about `centre`, counter-clockwise.
inline std::vector<Vec2> regular_polygon(Vec2 centre, double radius, int n) {
    std::vector<Vec2> p;
    for (int k = 0; k < n; ++k) {
        const double a = 2.0 * std::numbers::pi * k / n;
        p.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)});
    }
    return p;
}

/// A λ in the unit square: a long stroke from bottom right to top left, a short leg from
/// bottom left joining it, a notch between the legs. Counter-clockwise, concave at the notch
/// and the joint.
inline std::vector<Vec2> unit_lambda() {
    return {{0.0, 0.0}, {0.15, 0.0}, {0.5, 0.4},  {0.85, 0.0},
            {1.0, 0.0}, {0.3, 1.0},  {0.15, 1.0}, {0.42, 0.55}};
}

/// `per_edge` points on each edge of a closed polygon (its vertices included).
inline std::vector<Vec2> densify(std::span<const Vec2> poly, int per_edge) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i];
        const Vec2 b = poly[(i + 1) % poly.size()];
        for (int k = 0; k < per_edge; ++k)
            out.push_back(lerp(a, b, static_cast<double>(k) / per_edge));
    }
    return out;
}

/// An nx x ny grid of points covering the rectangle, inclusive of its corners.
inline std::vector<Vec2> grid_points(const Rect& r, int nx, int ny) {
    std::vector<Vec2> out;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            out.push_back(
                {r.min.x + r.width() * i / (nx - 1), r.min.y + r.height() * j / (ny - 1)});
        }
    }
    return out;
}

/// `count` uniformly random points in the rectangle (test generator, not the terrain's).
inline std::vector<Vec2> random_points_in(const Rect& r, std::size_t count, std::uint64_t seed) {
    std::mt19937_64 rng = test_rng(seed);
    std::uniform_real_distribution<double> ux(r.min.x, r.max.x);
    std::uniform_real_distribution<double> uy(r.min.y, r.max.y);
    std::vector<Vec2> out(count);
    for (Vec2& p : out)
        p = {ux(rng), uy(rng)};
    return out;
}

inline std::vector<double> surface_at(const Tin& tin, std::span<const Vec2> pts) {
    std::vector<double> out;
    out.reserve(pts.size());
    LocateHint hint;
    for (Vec2 p : pts)
        out.push_back(tin.height_at(p, &hint).value_or(std::nan("")));
    return out;
}

/// Steepest edge of the terrain: max |dh| / |dxy| over all triangle edges.
inline double steepest_edge(const Tin& tin) {
    double worst = 0.0;
    for (const Tri& t : tin.triangles()) {
        for (int i = 0; i < 3; ++i) {
            const VertexId a = t[static_cast<std::size_t>(i)];
            const VertexId b = t[static_cast<std::size_t>((i + 1) % 3)];
            const double run = distance(tin.position(a), tin.position(b));
            worst = std::max(worst, std::abs(tin.height(a) - tin.height(b)) / run);
        }
    }
    return worst;
}

/// check_valid() plus the CGAL-free mesh checks of tin_oracles.hpp, with two adjustments for
/// sculpted terrains:
///  - lumped areas are compared with an absolute floor of 1e-15 of the domain area (a sliver's
///    1e-20 m^2 star cannot be matched to 1e-9 relative in double precision, and does not
///    matter for volumes);
///  - no edge may be steeper than 1e4 (rise over run): the outer contour keeps a gap from the
///    inner one precisely so that no edge of the terrain is ever vertical (the tools' gaps
///    make slopes of at most depth / gap, about 100 for the shipped tools), so a steeper edge
///    is a near-duplicate vertex at another height.
inline ::testing::AssertionResult mesh_is_sound(const Tin& tin) {
    const ValidationReport r = tin.check_valid();
    if (!r.ok()) return ::testing::AssertionFailure() << "check_valid: " << r.summary();
    std::vector<std::string> problems;
    for (const std::string& p : mesh_problems(tin)) {
        if (p.find("lumped area") == std::string::npos) problems.push_back(p);
    }
    const std::vector<double> lumped = brute_force_lumped_areas(tin);
    const double floor = 1e-15 * tin.domain().width() * tin.domain().height();
    for (VertexId v : live_ids(tin)) {
        const double a = tin.vertices().lumped_area[v.index()];
        if (!close_rel(a, lumped[v.index()], 1e-9, floor) && problems.size() < 10) {
            problems.push_back("lumped area of vertex " + std::to_string(v.value) + " is " +
                               std::to_string(a) + ", its triangles give " +
                               std::to_string(lumped[v.index()]));
        }
    }
    const double steepest = steepest_edge(tin);
    if (steepest > 1e4) {
        problems.push_back("an edge rises " + std::to_string(steepest) +
                           " times its length: a near-vertical sliver");
    }
    if (!problems.empty()) return ::testing::AssertionFailure() << join(problems);
    return ::testing::AssertionSuccess();
}

/// A terrain of `count` random points plus points every `border_spacing` metres along the
/// domain border, so the surface near the border is as smooth as inside (Tin::random_points
/// has only the corners there, which makes slivers whose surface has cliffs).
inline Tin smooth_terrain(const Rect& domain, std::size_t count, std::uint64_t seed,
                          const Tin::HeightFunction& height, double border_spacing = 0.01) {
    std::vector<Vec2> pts = random_points_in(domain, count, seed);
    const int nx = static_cast<int>(std::ceil(domain.width() / border_spacing));
    const int ny = static_cast<int>(std::ceil(domain.height() / border_spacing));
    for (int i = 0; i <= nx; ++i) {
        const double x = i == nx ? domain.max.x : domain.min.x + domain.width() * i / nx;
        pts.push_back({x, domain.min.y});
        pts.push_back({x, domain.max.y});
    }
    for (int j = 1; j < ny; ++j) {
        const double y = domain.min.y + domain.height() * j / ny;
        pts.push_back({domain.min.x, y});
        pts.push_back({domain.max.x, y});
    }
    std::vector<double> hs;
    for (Vec2 p : pts)
        hs.push_back(height(p));
    TinOptions options;
    options.track_changes = false;
    return Tin::from_points(domain, pts, hs, options);
}

/// Bumpy sand: far from any plane at the scale of a patch (a few centimetres).
inline double bumpy_sand(Vec2 p) {
    return 0.2 + 0.03 * std::sin(41.0 * p.x + 0.4) * std::cos(37.0 * p.y - 0.1) +
           0.05 * (p.x - 0.5) * (p.x - 0.5);
}

/// Wavy sand, partly below the floors the stamp tests dig to, so a dig keeps some sand below
/// the tool.
inline double wavy_sand(Vec2 p) {
    return 0.1 + 0.03 * std::sin(20.0 * p.x) * std::cos(17.0 * p.y) + 0.02 * p.y;
}

/// Rolling sand: smooth, curved in both directions, well above z = 0.
inline double rolling_sand(Vec2 p) {
    return 0.1 + 0.02 * std::sin(7.0 * p.x + 0.3) * std::cos(5.0 * p.y - 0.2) + 0.01 * p.x;
}

/// An imported elevation model in the editing tests: 400 points over 500 m of rolling hills, so
/// each triangle is tens of metres wide and far from flat.
inline Tin coarse_hills_model() {
    return Tin::random_points(Rect::from_size(500.0, 500.0), 400, 71, [](Vec2 p) {
        return 100.0 + 40.0 * std::sin(p.x / 60.0) * std::cos(p.y / 45.0) + 0.05 * p.x;
    });
}

/// Where the coarse-model tests press a tool: in a triangle, on a vertex, next to one, and
/// (with `on_edge`) on the midpoint of an edge.
inline std::vector<Vec2> coarse_model_placements(const Tin& model, bool on_edge) {
    const std::vector<VertexId> ids = live_ids(model);
    std::vector<Vec2> places = {
        {203.0, 207.0}, model.position(ids[57]), model.position(ids[58]) + Vec2{0.2, -0.1}};
    if (on_edge) {
        std::vector<VertexId> next_to;
        model.neighbours(ids[60], next_to);
        places.push_back((model.position(ids[60]) + model.position(next_to[0])) * 0.5);
    }
    return places;
}

inline std::vector<Vec2> rotate_all(std::span<const Vec2> pts, Vec2 centre, double angle) {
    std::vector<Vec2> out;
    for (Vec2 p : pts)
        out.push_back(centre + rotate(p, angle));
    return out;
}

}  // namespace sandtin::test
