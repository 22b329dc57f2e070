// Strokes: arc-length sampling independent of how the path arrived, Catmull-Rom densification,
// and a long random stroke whose constraint and vertex counts must plateau. Oracles: arc length
// re-measured along the polyline, an independent Hermite evaluation of the centripetal
// Catmull-Rom curve, the same stroke on two terrains compared point by point.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "support/slivers.hpp"
#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/stamp.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"

namespace sandtin {
namespace {

using test::mesh_is_sound;

std::vector<StrokeSample> sample_path(std::span<const Vec2> path, double spacing) {
    StrokeSampler sampler(spacing);
    std::vector<StrokeSample> out;
    for (Vec2 p : path) {
        for (const StrokeSample& s : sampler.add_point(p))
            out.push_back(s);
    }
    for (const StrokeSample& s : sampler.finish())
        out.push_back(s);
    return out;
}

/// The polyline with each segment cut at random places (and some points repeated), as a
/// mouse at an irregular frame rate would deliver it.
std::vector<Vec2> resampled(std::span<const Vec2> path, std::uint64_t seed) {
    std::mt19937_64 rng = test::test_rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> pieces(1, 60);
    std::vector<Vec2> out = {path[0]};
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        std::vector<double> ts(static_cast<std::size_t>(pieces(rng)));
        for (double& t : ts)
            t = u(rng);
        std::sort(ts.begin(), ts.end());
        for (double t : ts) {
            out.push_back(lerp(path[i], path[i + 1], t));
            if (u(rng) < 0.1) out.push_back(out.back());  // a frame without motion
        }
        out.push_back(path[i + 1]);
    }
    return out;
}

/// Arc length of the point q along the polyline (q must lie on it).
double arc_length_of(std::span<const Vec2> path, Vec2 q) {
    double before = 0.0;
    double best_d = 1e9, best_s = -1.0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const double d = test::distance_to_segment_ld(q, path[i], path[i + 1]);
        if (d < best_d) {
            best_d = d;
            best_s = before + distance(path[i], q);
        }
        before += distance(path[i], path[i + 1]);
    }
    EXPECT_LE(best_d, 1e-13) << "sample off the path";
    return best_s;
}

const std::vector<Vec2> kPolyline = {{0.1, 0.2}, {0.63, 0.31}, {0.55, 0.77}, {0.2, 0.83}};

TEST(Stroke, SamplerSpacesSamplesByArcLength) {
    const double spacing = 0.0137;
    // Straight: consecutive samples exactly `spacing` apart.
    const std::vector<Vec2> line = {{0.1, 0.1}, {0.8, 0.45}};
    const std::vector<StrokeSample> s = sample_path(line, spacing);
    const double len = distance(line[0], line[1]);
    ASSERT_EQ(s.size(), static_cast<std::size_t>(std::floor(len / spacing)) + 1);
    EXPECT_EQ(s[0].position, line[0]);
    for (std::size_t k = 1; k < s.size(); ++k)
        EXPECT_NEAR(distance(s[k - 1].position, s[k].position), spacing, 1e-12);
    // A polyline with corners: samples every `spacing` metres of path, wherever they fall.
    const std::vector<StrokeSample> p = sample_path(kPolyline, spacing);
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < kPolyline.size(); ++i)
        total += distance(kPolyline[i], kPolyline[i + 1]);
    ASSERT_EQ(p.size(), static_cast<std::size_t>(std::floor(total / spacing)) + 1);
    for (std::size_t k = 0; k < p.size(); ++k) {
        EXPECT_NEAR(p[k].arc_length, k * spacing, 1e-12);
        EXPECT_NEAR(arc_length_of(kPolyline, p[k].position), k * spacing, 1e-12);
        ASSERT_TRUE(p[k].direction.has_value());
        EXPECT_NEAR(length(*p[k].direction), 1.0, 1e-15);
    }
}

TEST(Stroke, SamplerIsIndependentOfHowThePathArrived) {
    const double spacing = 0.01;
    const std::vector<StrokeSample> coarse = sample_path(kPolyline, spacing);
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        const std::vector<Vec2> fine = resampled(kPolyline, seed);
        ASSERT_GT(fine.size(), 20u);
        const std::vector<StrokeSample> s = sample_path(fine, spacing);
        ASSERT_EQ(s.size(), coarse.size());
        for (std::size_t k = 0; k < s.size(); ++k) {
            EXPECT_NEAR(s[k].position.x, coarse[k].position.x, 1e-12);
            EXPECT_NEAR(s[k].position.y, coarse[k].position.y, 1e-12);
            ASSERT_TRUE(s[k].direction && coarse[k].direction);
            EXPECT_NEAR(s[k].direction->x, coarse[k].direction->x, 1e-12);
            EXPECT_NEAR(s[k].direction->y, coarse[k].direction->y, 1e-12);
            EXPECT_NEAR(s[k].arc_length, coarse[k].arc_length, 1e-12);
        }
    }
}

// A path a whole number of spacings long ends on a sample, whatever the last bit of
// length / spacing: 0.2 -> 0.5 at 0.1 (2.9999999999999996 spacings in doubles) used to stop
// at 0.4, while 0.1 -> 0.4 (3.0000000000000004) reached 0.4, and the same scene got 49 stamps
// at 1 m and 48 at 1 cm. Oracle: the exact count, k + 1 samples over k spacings, with the last
// one on the end, at every scale.
TEST(Stroke, APathAWholeNumberOfSpacingsLongEndsOnASampleAtEveryScale) {
    for (const double scale : {0.01, 1.0, 1000.0, 1e5}) {
        for (const auto& [from, to, spacing, spacings] :
             std::vector<std::tuple<double, double, double, int>>{{0.2, 0.5, 0.1, 3},
                                                                  {0.1, 0.4, 0.1, 3},
                                                                  {0.25, 0.75, 0.125, 4},
                                                                  {0.3, 0.9, 0.01, 60},
                                                                  {0.0, 0.7, 0.1, 7}}) {
            SCOPED_TRACE(std::to_string(scale) + " m: " + std::to_string(from) + " -> " +
                         std::to_string(to) + " at " + std::to_string(spacing));
            const std::vector<Vec2> path = {{from * scale, 0.6 * scale}, {to * scale, 0.6 * scale}};
            const std::vector<StrokeSample> s = sample_path(path, spacing * scale);
            ASSERT_EQ(s.size(), static_cast<std::size_t>(spacings + 1));
            EXPECT_NEAR(s.back().position.x, to * scale, 1e-12 * scale);
            EXPECT_LE(s.back().position.x, to * scale) << "a sample beyond the path's end";
        }
    }
    // Short of a whole spacing the end is not stamped: samples stay a spacing apart.
    const std::vector<Vec2> short_path = {{0.2, 0.6}, {0.49, 0.6}};
    const std::vector<StrokeSample> s = sample_path(short_path, 0.1);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_NEAR(s.back().position.x, 0.4, 1e-15);
}

TEST(Stroke, SingleClickGivesOneSample) {
    StrokeSampler sampler(0.01);
    EXPECT_TRUE(sampler.add_point({0.3, 0.4}).empty());
    EXPECT_TRUE(sampler.add_point({0.3, 0.4}).empty());  // no motion
    const std::vector<StrokeSample> s = sampler.finish();
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].position, (Vec2{0.3, 0.4}));
    EXPECT_TRUE(sampler.finish().empty());
    // A short move emits the start point once, and finish() adds nothing.
    StrokeSampler moved(0.01);
    moved.add_point({0.3, 0.4});
    EXPECT_EQ(moved.add_point({0.3, 0.405}).size(), 1u);
    EXPECT_TRUE(moved.finish().empty());
    EXPECT_THROW(StrokeSampler(0.0), std::invalid_argument);
    EXPECT_THROW(StrokeSampler(std::nan("")), std::invalid_argument);
    StrokeSampler bad(0.01);
    EXPECT_THROW(bad.add_point({std::nan(""), 0.0}), std::invalid_argument);
}

TEST(Stroke, TerrainIsIndependentOfHowThePathArrived) {
    const Tool tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.spacing = 0.01;
    settings.depth = 0.01;
    settings.depth_mode = DepthMode::Relative;
    Tin a = Tin::random_points(Rect::from_size(1, 1), 3000, 91, test::rolling_sand);
    Tin b = Tin::random_points(Rect::from_size(1, 1), 3000, 91, test::rolling_sand);
    SculptContext ca(a.domain()), cb(b.domain());
    std::vector<StampReport> ra, rb;
    apply_stroke(a, tool, kPolyline, settings, ca, &ra);
    const std::vector<Vec2> fine = resampled(kPolyline, 7);
    apply_stroke(b, tool, fine, settings, cb, &rb);
    EXPECT_EQ(ra.size(), rb.size());
    EXPECT_EQ(ra.size(), sample_path(kPolyline, settings.spacing).size());
    EXPECT_TRUE(mesh_is_sound(a));
    EXPECT_TRUE(mesh_is_sound(b));
    const std::vector<Vec2> grid = test::grid_points(Rect::from_size(1, 1), 151, 151);
    const std::vector<double> ha = test::surface_at(a, grid);
    const std::vector<double> hb = test::surface_at(b, grid);
    double worst = 0.0;
    for (std::size_t i = 0; i < grid.size(); ++i)
        worst = std::max(worst, std::abs(ha[i] - hb[i]));
    EXPECT_LE(worst, 1e-9);
    EXPECT_NEAR(a.volume(), b.volume(), 1e-12);
    // The stroke dug a groove (the oracle sees something to compare).
    EXPECT_LT(*a.height_at({0.4, 0.8}), test::rolling_sand({0.4, 0.8}) - 0.005);
}

// ---- Catmull-Rom ----------------------------------------------------------------------------

/// The centripetal Catmull-Rom segment from c[i] to c[i+1] in Hermite form: tangents of the
/// Barry-Goldman curve at its knots, t_{j+1} - t_j = sqrt(|c_{j+1} - c_j|).
struct HermiteSegment {
    Vec2 p1, p2, m1, m2;
    Vec2 at(double u) const {
        const double u2 = u * u, u3 = u2 * u;
        return p1 * (2 * u3 - 3 * u2 + 1) + m1 * (u3 - 2 * u2 + u) + p2 * (-2 * u3 + 3 * u2) +
               m2 * (u3 - u2);
    }
};

HermiteSegment hermite(std::span<const Vec2> c, std::size_t i) {
    const Vec2 p0 = c[i - 1], p1 = c[i], p2 = c[i + 1], p3 = c[i + 2];
    const double d01 = std::sqrt(distance(p0, p1));
    const double d12 = std::sqrt(distance(p1, p2));
    const double d23 = std::sqrt(distance(p2, p3));
    const Vec2 v1 = (p1 - p0) / d01 - (p2 - p0) / (d01 + d12) + (p2 - p1) / d12;
    const Vec2 v2 = (p2 - p1) / d12 - (p3 - p1) / (d12 + d23) + (p3 - p2) / d23;
    return {p1, p2, v1 * d12, v2 * d12};
}

/// Distance from q to the curve segment (dense search, then ternary refinement).
double distance_to_curve(const HermiteSegment& h, Vec2 q) {
    const int n = 400;
    int best = 0;
    for (int k = 1; k <= n; ++k) {
        if (distance(h.at(static_cast<double>(k) / n), q) <
            distance(h.at(static_cast<double>(best) / n), q))
            best = k;
    }
    double lo = std::max(0.0, (best - 1.0) / n), hi = std::min(1.0, (best + 1.0) / n);
    for (int it = 0; it < 200; ++it) {
        const double a = lo + (hi - lo) / 3.0, b = hi - (hi - lo) / 3.0;
        if (distance(h.at(a), q) < distance(h.at(b), q)) {
            hi = b;
        } else {
            lo = a;
        }
    }
    return distance(h.at(0.5 * (lo + hi)), q);
}

TEST(Stroke, CatmullRomPassesThroughControlsAndFollowsThePolygon) {
    const std::vector<Vec2> c = {{0.0, 0.0},  {0.1, 0.02}, {0.15, 0.1},  {0.3, 0.12},
                                 {0.32, 0.3}, {0.5, 0.25}, {0.52, 0.26}, {0.9, 0.2}};
    const double max_step = 0.01;
    const std::vector<Vec2> curve = catmull_rom(c, max_step);
    ASSERT_GT(curve.size(), c.size());
    EXPECT_EQ(curve.front(), c.front());
    EXPECT_NEAR(distance(curve.back(), c.back()), 0.0, 1e-15);
    // Through every control point, in order.
    std::vector<std::size_t> at(c.size());
    std::size_t from = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        bool found = false;
        for (std::size_t k = from; k < curve.size() && !found; ++k) {
            if (distance(curve[k], c[i]) <= 1e-15) {
                at[i] = k;
                from = k + 1;
                found = true;
            }
        }
        EXPECT_TRUE(found) << "control point " << i << " is not on the curve";
    }
    // Densified to the step: no piece longer than max_step (documented).
    double longest = 0.0;
    std::size_t too_long = 0;
    for (std::size_t k = 1; k < curve.size(); ++k) {
        longest = std::max(longest, distance(curve[k - 1], curve[k]));
        too_long += distance(curve[k - 1], curve[k]) > max_step * (1.0 + 1e-9) ? 1 : 0;
    }
    EXPECT_EQ(too_long, 0u) << too_long << " of " << curve.size() - 1
                            << " pieces are longer than max_step = " << max_step
                            << "; the longest is " << longest;
    // Close to the control polygon: within half of the longest adjacent control segment.
    for (std::size_t i = 0; i + 1 < c.size(); ++i) {
        double reach = distance(c[i], c[i + 1]);
        if (i > 0) reach = std::max(reach, distance(c[i - 1], c[i]));
        if (i + 2 < c.size()) reach = std::max(reach, distance(c[i + 1], c[i + 2]));
        for (std::size_t k = at[i]; k <= at[i + 1]; ++k)
            EXPECT_LE(test::distance_to_segment_ld(curve[k], c[i], c[i + 1]), 0.5 * reach);
    }
    // On the centripetal curve itself (interior segments, which need no end conditions).
    for (std::size_t i = 1; i + 2 < c.size(); ++i) {
        const HermiteSegment h = hermite(c, i);
        for (std::size_t k = at[i]; k <= at[i + 1]; ++k)
            EXPECT_LE(distance_to_curve(h, curve[k]), 1e-12) << "segment " << i << " point " << k;
    }
    // Collinear controls give a straight line.
    const std::vector<Vec2> straight = {{0, 0}, {0.1, 0.05}, {0.5, 0.25}, {0.6, 0.3}};
    for (Vec2 p : catmull_rom(straight, 0.01))
        EXPECT_NEAR(test::distance_to_segment_ld(p, straight.front(), straight.back()), 0.0, 1e-15);
    // Fewer than three points: returned as they are.
    const std::vector<Vec2> two = {{0, 0}, {1, 1}};
    EXPECT_EQ(catmull_rom(two, 0.01), two);
}

// ---- 1 000 stamps ---------------------------------------------------------------------------

/// A random walk with steps of `step` metres that bounces off the walls of [lo, hi]^2.
class RandomWalk {
  public:
    RandomWalk(std::uint64_t seed, double lo, double hi, double step)
        : rng_(test::test_rng(seed)), lo_(lo), hi_(hi), step_(step) {}
    StrokeSample next() {
        heading_ += turn_(rng_);
        Vec2 q = p_ + Vec2{std::cos(heading_), std::sin(heading_)} * step_;
        if (q.x < lo_ || q.x > hi_) heading_ = std::numbers::pi - heading_;
        if (q.y < lo_ || q.y > hi_) heading_ = -heading_;
        const Vec2 dir{std::cos(heading_), std::sin(heading_)};
        p_ = p_ + dir * step_;
        travelled_ += step_;
        return {p_, dir, travelled_};
    }

  private:
    std::mt19937_64 rng_;
    std::normal_distribution<double> turn_{0.0, 0.6};
    double lo_, hi_, step_;
    Vec2 p_{0.5, 0.5};
    double heading_ = 0.3;
    double travelled_ = 0.0;
};

TEST(Stroke, ThousandStampRandomStrokeStaysValidAndBounded) {
    // A random walk with 0.01 m steps, the circle tool (r 0.04) 5 mm below the sand ahead of
    // it (the stroke's relative depth), over rolling sand of 10 000 points. The walk stays in
    // the central 0.4 m square of the unit domain, so after a few hundred stamps it only
    // re-digs ground it has covered: the terrain it makes stops growing in extent, and the
    // counts must stop growing too. (Unconfined, the dug area itself keeps growing and with
    // it the number of vertices its walls genuinely need.)
    Tin tin = Tin::random_points(Rect::from_size(1, 1), 10000, 101, test::rolling_sand);
    SculptContext context(tin.domain());
    const Tool tool = Tool::build(load_tool_asset("circle"));
    StrokeSettings settings;
    settings.spacing = 0.01;
    settings.depth = 0.005;
    settings.depth_mode = DepthMode::Relative;
    RandomWalk walk(103, 0.3, 0.7, settings.spacing);
    const int n = 1000;
    std::vector<double> vertices(n + 1), constraints(n + 1), edges(n + 1);
    auto record = [&](int k) {
        vertices[static_cast<std::size_t>(k)] = static_cast<double>(tin.vertex_count());
        constraints[static_cast<std::size_t>(k)] = static_cast<double>(tin.constraint_count());
        edges[static_cast<std::size_t>(k)] = static_cast<double>(tin.constrained_edge_count());
    };
    record(0);
    const double volume0 = tin.volume();
    double ledger_of_stamps = 0.0;
    Generation last_generation = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 1; k <= n; ++k) {
        const StrokeSample sample = walk.next();
        const ToolPlacement at = placement_for(tin, tool, sample, settings, &context.hint);
        const StampReport r = stamp(tin, tool, at, context, sample.direction);
        ASSERT_TRUE(r.applied);
        ledger_of_stamps += r.volume_change;
        last_generation = r.generation;
        record(k);
        if (k % 100 == 0) {
            const ValidationReport v = tin.check_valid();
            ASSERT_TRUE(v.ok()) << "after " << k << " stamps: " << v.summary();
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(mesh_is_sound(tin));
    // The stamps' reports account for the whole volume change, and the stroke dug.
    EXPECT_NEAR(tin.volume() - volume0, ledger_of_stamps, 1e-9);
    EXPECT_LT(tin.volume(), volume0);
    // Constraints of stamps more than keep_generations old come of age: each is released at a
    // look where releasing it leaves the triangulation as it is (all pieces Delaunay), and one
    // that cannot go is looked at again after doubling waits. So at the end the expired
    // constraints that are all Delaunay (independent in-circle test) are the few waiting for
    // their next look, and releasing exactly those re-triangulates nothing: the surface and
    // its volume stay as they are.
    {
        const auto not_delaunay = test::edges_not_clearly_delaunay(tin);
        const Generation limit = last_generation + 1 - context.settings.keep_generations;
        std::size_t expired = 0;
        std::size_t waiting = 0;
        for (const ConstraintInfo& c : tin.constraints()) {
            if (c.generation >= limit) continue;
            ++expired;
            bool has_non_delaunay_piece = false;
            for (std::size_t k = 0; k + 1 < c.vertices.size(); ++k) {
                std::uint32_t a = c.vertices[k].value, b = c.vertices[k + 1].value;
                if (a > b) std::swap(a, b);
                has_non_delaunay_piece = has_non_delaunay_piece || not_delaunay.count({a, b}) > 0;
            }
            if (!has_non_delaunay_piece) ++waiting;
        }
        std::cout << "[ info     ] expired constraints " << expired << ", all-Delaunay " << waiting
                  << "\n";
        EXPECT_LE(waiting, expired / 4 + 5);
        const std::vector<double> heights_before = tin.vertices().height;
        const std::size_t vertices_before = tin.vertex_count();
        const double volume_before = tin.volume();
        ReleaseFilter sweep;
        sweep.older_than = limit;
        sweep.only_if_delaunay = true;
        EXPECT_EQ(tin.release_constraints(sweep, VolumePolicy::Report), waiting);
        EXPECT_EQ(tin.vertex_count(), vertices_before);
        EXPECT_EQ(tin.vertices().height, heights_before);
        EXPECT_NEAR(tin.volume(), volume_before, 1e-15);
        EXPECT_TRUE(tin.check_valid().ok());
    }

    // Plateau. The criterion compares the growth over the last 300 stamps with the growth
    // over the first 300, each measured between 25-stamp averages to smooth the stamp-to-stamp
    // jitter. A count that grows linearly grows equally in both windows (ratio 1); one that
    // saturates once the walk has covered its square grows much less in the last. Required:
    // last <= first / 3, plus 1 % of the count for a plateau that merely fluctuates.
    auto mean = [](const std::vector<double>& c, int from) {
        double s = 0.0;
        for (int i = from; i < from + 25; ++i)
            s += c[static_cast<std::size_t>(i)];
        return s / 25.0;
    };
    for (const auto& [name, c] :
         {std::pair{"vertices", &vertices}, std::pair{"constraints", &constraints},
          std::pair{"constrained edges", &edges}}) {
        const double first = mean(*c, 276) - mean(*c, 0);
        const double last = mean(*c, 976) - mean(*c, 700);
        const double level = mean(*c, 976);
        EXPECT_LE(last, first / 3.0 + 0.01 * level)
            << name << ": +" << first << " over the first 300 stamps, +" << last
            << " over the last 300; " << (*c)[0] << " -> " << (*c)[n];
    }
    std::cout << "[ info     ] 1000 stamps in " << seconds << " s; vertices " << vertices[0]
              << " -> " << vertices[n] << ", constraints " << constraints[n] << "\n";
}

TEST(Stroke, DugSandStaysDugAlongARandomStroke) {
    // Dig only ever lowers sand, and without extrusion nothing else raises it: after a stroke
    // at a constant floor, every point whose last covering tool had it inside its inner contour
    // must be at the floor (up to the simplifier's tolerance, as removals may shift heights to
    // conserve volume; exactly without simplification). Points whose last covering tool had
    // them in its wall band (inside O, outside I) are that tool's ramp and are not checked:
    // the ramp interpolates between the floor and the surface at O, which may stand above an
    // earlier stamp's floor (a known limitation of a piecewise-linear wall, see DESIGN §5).
    for (const bool simplify : {true, false}) {
        SCOPED_TRACE(simplify ? "with simplification" : "without simplification");
        Tin tin = Tin::random_points(Rect::from_size(1, 1), 10000, 111, test::rolling_sand);
        SculptContext context(tin.domain());
        context.settings.simplify_after_edit = simplify;
        const Tool tool = Tool::build(load_tool_asset("circle"));
        StrokeSettings settings;
        settings.spacing = 0.01;
        settings.depth = 0.05;  // below the sand everywhere (>= 0.08 m)
        settings.depth_mode = DepthMode::Absolute;
        RandomWalk walk(113, 0.3, 0.7, settings.spacing);
        struct Footprint {
            Vec2 centre;
            std::vector<Vec2> inner, outer;
        };
        std::vector<Footprint> footprints;
        for (int k = 0; k < 300; ++k) {
            const StrokeSample sample = walk.next();
            const ToolPlacement at = placement_for(tin, tool, sample, settings, &context.hint);
            ASSERT_TRUE(stamp(tin, tool, at, context, sample.direction).applied);
            footprints.push_back({at.centre,
                                  test::rotate_all(tool.shape().inner, at.centre, at.angle),
                                  test::rotate_all(tool.shape().outer, at.centre, at.angle)});
        }
        EXPECT_TRUE(mesh_is_sound(tin));
        double reach = 0.0;  // circumradius of O about the centre
        for (Vec2 q : tool.shape().outer)
            reach = std::max(reach, distance(q, Vec2{0.0, 0.0}));
        const double tol = simplify ? context.settings.simplify.tolerance : 1e-12;
        std::size_t covered = 0, raised = 0, raised_cm = 0;
        double worst = 0.0;
        Vec2 worst_at;
        LocateHint hint;
        for (Vec2 p : test::grid_points(Rect{{0.2, 0.2}, {0.8, 0.8}}, 241, 241)) {
            const Footprint* last = nullptr;
            for (auto f = footprints.rbegin(); f != footprints.rend() && !last; ++f) {
                if (distance(p, f->centre) <= reach + 1e-9 && test::inside_by(p, f->outer, 0.0))
                    last = &*f;
            }
            if (!last || !test::inside_by(p, last->inner, 1e-9)) continue;
            ++covered;
            const double h = *tin.height_at(p, &hint);
            if (h > settings.depth + tol) {
                ++raised;
                raised_cm += h > settings.depth + 0.01 ? 1 : 0;
                if (h - settings.depth > worst) worst_at = p;
                worst = std::max(worst, h - settings.depth);
            }
        }
        EXPECT_GT(covered, 10000u);
        // Two effects may lift a handful of points by a few millimetres: forcing a later rim
        // through an enlarged floor triangle (with simplification), and flips across an expired,
        // released inner rim when later stamps insert nearby, which re-triangulate the floor's
        // edge against the wall band. Allow 0.1 % of the points, never a centimetre.
        const std::size_t allowed = covered / 1000;
        EXPECT_LE(raised, allowed)
            << raised << " of " << covered << " dug points stand above the floor, by up to "
            << worst << " m (at " << worst_at.x << ", " << worst_at.y << ")";
        EXPECT_EQ(raised_cm, 0u);
    }
}

// A tool stroked along one of its straight sides (the box, the λ) puts each stamp's rim on the
// line of the one before. Kept, the older rim ran a hair beside the new one, and between two
// constraints that close only triangles without area fit: the λ groove left 428 vertices with
// under a millionth of a neighbour's area (vertical slivers the sand crept through forever)
// and the box 34. The stamp releases an older constraint along its border as one inside it,
// so none is left.
TEST(Stroke, ToolsStrokedAlongAStraightSideLeaveNoVerticalSlivers) {
    for (const char* asset : {"box", "lambda"}) {
        SCOPED_TRACE(asset);
        Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 10000, 2009);
        SculptContext context(tin.domain());
        StrokeSettings settings;
        settings.spacing = 0.01;
        settings.depth_mode = DepthMode::Absolute;
        settings.depth = -0.1;
        const std::vector<Vec2> path = {{0.1, 0.1}, {0.9, 0.9}};
        apply_stroke(tin, Tool::build(load_tool_asset(asset)), path, settings, context);
        EXPECT_EQ(test::sliver_vertices(tin), 0u);
        EXPECT_TRUE(tin.check_valid().ok());
        RecordProperty(std::string(asset) + "_constraints",
                       static_cast<int>(tin.constraint_count()));
    }
}

/// The highest and lowest surface along the line through `from` in direction `d` (unit), at
/// arc lengths [a, b] every 0.2 mm.
std::pair<double, double> height_range_along(const Tin& tin, Vec2 from, Vec2 d, double a,
                                             double b) {
    LocateHint hint;
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (double s = a; s <= b; s += 2e-4) {
        const double h = *tin.height_at(from + d * s, &hint);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    return {lo, hi};
}

// ---- Clicks and depth ------------------------------------------------------------------------

/// The rise of the surface over `before` in four quarters around `centre` (+x, +y, -x, -y),
/// integrated on a grid of the square `half` metres around it.
std::array<double, 4> rise_by_quarter(const Tin& tin, const Tin& before, Vec2 centre, double half) {
    std::array<double, 4> q{};
    constexpr int kN = 240;
    const double cell = (2.0 * half / kN) * (2.0 * half / kN);
    LocateHint h0, h1;
    for (int j = 0; j < kN; ++j) {
        for (int i = 0; i < kN; ++i) {
            const Vec2 r{-half + 2.0 * half * (i + 0.5) / kN, -half + 2.0 * half * (j + 0.5) / kN};
            const double rise =
                *tin.height_at(centre + r, &h1) - *before.height_at(centre + r, &h0);
            if (!(rise > 0.0)) continue;
            const std::size_t k =
                std::abs(r.x) >= std::abs(r.y) ? (r.x > 0.0 ? 0 : 2) : (r.y > 0.0 ? 1 : 3);
            q[k] += rise * cell;
        }
    }
    return q;
}

// A click (a press without moving) stamps once with no motion, and stamp() then puts the ridge
// all around the tool. The sampler used to report the direction (1, 0) for a path that never
// moved, and the editor passed it on as the motion: a click of the circle or the ball put all
// of its ridge on the +x side. The same through apply_stroke with a path that never parts.
// Oracle: on flat sand the four quarters around the tool get the same sand, to discretisation,
// and the terrain keeps its volume.
TEST(Stroke, AClickPutsItsRidgeAllAround) {
    const Vec2 c{0.5, 0.5};
    const double level = 0.1;
    for (const char* asset : {"circle", "ball"}) {
        ToolSpec spec = load_tool_asset(asset);
        spec.extrude = true;
        const Tool tool = Tool::build(spec);
        StrokeSettings settings;
        settings.spacing = 0.25 * tool.radius();
        settings.depth = 0.015;
        for (const int how : {0, 1, 2}) {
            SCOPED_TRACE(std::string(asset) + (how == 0   ? ": sampler, placement_for, stamp"
                                               : how == 1 ? ": apply_stroke, one point"
                                                          : ": apply_stroke, a point twice"));
            Tin tin = Tin::random_points(test::kUnitSquare, 40000, 47, [=](Vec2) { return level; });
            const Tin before = Tin::from_snapshot(tin.snapshot());
            SculptContext context(tin.domain());
            const double v0 = tin.volume();
            if (how == 0) {  // as the editor stamps a click
                StrokeSampler sampler(settings.spacing);
                EXPECT_TRUE(sampler.add_point(c).empty());
                EXPECT_TRUE(sampler.add_point(c).empty());
                const std::vector<StrokeSample> samples = sampler.finish();
                ASSERT_EQ(samples.size(), 1u);
                EXPECT_FALSE(samples[0].direction.has_value());
                const ToolPlacement at =
                    placement_for(tin, tool, samples[0], settings, &context.hint);
                EXPECT_NEAR(at.bottom, level - settings.depth, 1e-15);
                ASSERT_TRUE(stamp(tin, tool, at, context, samples[0].direction).applied);
            } else {
                const std::vector<Vec2> path(static_cast<std::size_t>(how), c);
                std::vector<StampReport> per;
                apply_stroke(tin, tool, path, settings, context, &per);
                ASSERT_EQ(per.size(), 1u);
            }
            EXPECT_TRUE(mesh_is_sound(tin));
            EXPECT_NEAR(tin.volume(), v0, 1e-12);
            const std::array<double, 4> q =
                rise_by_quarter(tin, before, c, tool.radius() + 2.0 * tool.extrusion_width());
            const double mean = 0.25 * (q[0] + q[1] + q[2] + q[3]);
            ASSERT_GT(mean, 0.0);
            for (std::size_t k = 0; k < 4; ++k)
                EXPECT_NEAR(q[k], mean, 0.1 * mean) << "quarter " << k << " (+x, +y, -x, -y)";
        }
    }
}

/// The surface along the segment from a to b, every 0.5 mm: its lowest and highest points.
std::pair<double, double> range_between(const Tin& tin, Vec2 a, Vec2 b) {
    const Vec2 d = (b - a) / distance(a, b);
    return height_range_along(tin, a, d, 0.0, distance(a, b));
}

// A stroke cuts the depth it was asked for below the sand it started from, all along, its start
// included. In relative mode the depth was taken below the terrain as it was at each stamp's
// leading edge, where the previous stamp's ridge stood: the ball stroke of the editor (radius
// 5 cm, 15 mm deep, a quarter of the radius apart) dug 15 mm at its first stamp, 10 mm two
// stamps on and 11 mm through its middle (3 mm with the editor's erosion between frames). It is
// now taken below the terrain as the stroke found it (StrokeGround). Oracle: the flat level
// minus the depth along the path's centre line, where the ball's lowest point passes (between
// two stamps 12.5 mm apart its underside stands 0.4 mm higher), with extrusion on and off,
// through apply_stroke and through a Stroke fed point by point as the editor's mouse does.
TEST(Stroke, CutsTheRequestedDepthAlongItsWholeLength) {
    const double level = 0.1;
    const double depth = 0.015;
    const Vec2 from{0.25, 0.4};
    const Vec2 to{0.75, 0.6};
    for (const bool extrude : {false, true}) {
        ToolSpec spec = load_tool_asset("ball");
        spec.radius = 0.05;
        spec.extrude = extrude;
        const Tool tool = Tool::build(spec);
        StrokeSettings settings;
        settings.spacing = 0.25 * tool.radius();
        settings.depth = depth;
        settings.depth_mode = DepthMode::Relative;
        for (const bool by_mouse : {false, true}) {
            SCOPED_TRACE(std::string(extrude ? "extrusion on, " : "extrusion off, ") +
                         (by_mouse ? "point by point" : "apply_stroke"));
            Tin tin = Tin::random_points(test::kUnitSquare, 40000, 53, [=](Vec2) { return level; });
            SculptContext context(tin.domain());
            const double v0 = tin.volume();
            std::vector<Vec2> stamped;
            if (by_mouse) {
                Stroke stroke(tool, settings);
                for (int k = 0; k <= 100; ++k) {
                    for (const StrokeStamp& s :
                         stroke.add_point(tin, lerp(from, to, k / 100.0), context))
                        stamped.push_back(s.placement.centre);
                }
                for (const StrokeStamp& s : stroke.finish(tin, context))
                    stamped.push_back(s.placement.centre);
            } else {
                std::vector<StampReport> per;
                apply_stroke(tin, tool, std::vector<Vec2>{from, to}, settings, context, &per);
                const std::vector<StrokeSample> samples =
                    sample_path(std::vector<Vec2>{from, to}, settings.spacing);
                ASSERT_EQ(per.size(), samples.size());
                for (const StrokeSample& s : samples)
                    stamped.push_back(s.position);
            }
            ASSERT_GT(stamped.size(), 40u);
            EXPECT_TRUE(mesh_is_sound(tin));
            if (extrude) {
                EXPECT_NEAR(tin.volume(), v0, 1e-12);
            }
            const auto [lo, hi] = range_between(tin, stamped.front(), stamped.back());
            EXPECT_GE(lo, level - depth - 0.5e-3) << "deeper than asked by " << level - depth - lo;
            EXPECT_LE(hi, level - depth + 1e-3)
                << "shallower than asked by " << hi - (level - depth);
        }
    }
}

// ---- Rake furrows -----------------------------------------------------------------------------

// The rake (five round tines across a 12 cm head, 3 cm long) dragged straight at a constant
// floor, at the editor's spacing (a quarter of its radius), leaves five continuous furrows:
// along the middle of each tine's path the sand stands at the floor, the tine tips' (black,
// the profile's lowest) height, within a twentieth of the depth, and 2 mm to either side within
// a fifth. Its strokes left rows of studs:
// - the inner contour I, enforced whole at the sand's height because the rake's edges stand
//   above the sand, had points only every 25 mm (about the tine pitch), and its back edge's
//   straight chords crossed the previous stamp's furrows at the height of the sand between
//   them, walling each furrow off at every stamp (the sand at the surface there: a variation
//   of the whole depth);
// - 15 mm apart, the stamps left the tines' flanks (shorter than their 18 mm middle)
//   scalloped: 2 mm beside the middle line the sand rose up to 6.6 mm between stamps, and the
//   middle line itself up to 0.9 mm; a stroke now keeps to the tool's max_stroke_spacing(),
//   half its shortest tip (9 mm): 1.6 mm and 0.3 mm.
// Oracles: the flat level, the floor, and the volume (with extrusion exactly kept; without,
// what the reports say). Through apply_stroke, and a Stroke fed point by point (the editor).
TEST(Stroke, ARakeStrokeLeavesContinuousFurrows) {
    const double level = 0.1;
    const double depth = 0.01;
    const Vec2 from{0.2, 0.45};
    const Vec2 to{0.8, 0.55};
    const Vec2 d = (to - from) / distance(from, to);
    const Vec2 across{-d.y, d.x};
    for (const bool extrude : {false, true}) {
        SCOPED_TRACE(extrude ? "extrusion on" : "extrusion off");
        ToolSpec spec = load_tool_asset("rake");
        spec.extrude = extrude;
        const Tool tool = Tool::build(spec);
        Tin tin = Tin::random_points(test::kUnitSquare, 40000, 43, [=](Vec2) { return level; });
        SculptContext context(tin.domain());
        StrokeSettings settings;
        settings.spacing = 0.25 * tool.radius();
        settings.depth_mode = DepthMode::Absolute;
        settings.depth = level - depth;
        EXPECT_EQ(Stroke(tool, settings).spacing(), tool.max_stroke_spacing());
        const double v0 = tin.volume();
        StampReport r;
        if (extrude) {
            const std::vector<Vec2> path = {from, to};
            r = apply_stroke(tin, tool, path, settings, context);
        } else {
            Stroke stroke(tool, settings);
            for (int k = 0; k <= 60; ++k) {
                for (const StrokeStamp& s :
                     stroke.add_point(tin, lerp(from, to, k / 60.0), context))
                    r.accumulate(s.report);
            }
            for (const StrokeStamp& s : stroke.finish(tin, context))
                r.accumulate(s.report);
        }
        EXPECT_TRUE(mesh_is_sound(tin));
        EXPECT_NEAR(tin.volume() - v0, r.volume_change, 1e-12);
        if (extrude) {
            EXPECT_NEAR(tin.volume(), v0, 1e-12);
        }
        // The tines' middles, 0, +-24 and +-48 mm across the head (the image's five pegs), and
        // 2 mm to either side, across the middle half of their tips' 8 mm width, whose steep
        // sides the terrain's triangles approximate less closely.
        const double length = distance(from, to);
        for (const double tine : {-0.048, -0.024, 0.0, 0.024, 0.048}) {
            for (const double beside : {-0.002, 0.0, 0.002}) {
                SCOPED_TRACE("tine at " + std::to_string(tine) + ", " + std::to_string(beside));
                const auto [lo, hi] = height_range_along(tin, from + across * (tine + beside), d,
                                                         0.03, length - 0.03);
                EXPECT_GE(lo, level - depth - 1e-4);
                EXPECT_LE(hi, level - depth + (beside == 0.0 ? 0.05 : 0.2) * depth)
                    << "the furrow rises " << hi - (level - depth) << " m above its floor";
            }
        }
    }
}

}  // namespace
}  // namespace sandtin
