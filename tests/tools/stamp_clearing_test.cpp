// The stamp's bulk clearing (SculptSettings::clear_before_imprint, tin/bulk_removal) is a
// speed-up only: it removes first what the stamp would remove anyway. Oracle: the same edits
// with the clearing off, on identical terrains, must leave the same vertices at the same
// heights and the same surface, on flat, curved and partly-below-the-floor sand, with round
// and non-convex tools, with and without simplification.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "support/tin_oracles.hpp"
#include "support/tool_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/simplifier.hpp"
#include "tools/stamp.hpp"
#include "tools/stroke.hpp"
#include "tools/tool.hpp"
#include "tools/tool_json.hpp"

namespace sandtin {
namespace {

double flat(Vec2) {
    return 0.0;
}

using Vertex = std::tuple<double, double, double>;

std::vector<Vertex> vertices_of(const Tin& tin) {
    std::vector<Vertex> out;
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        out.emplace_back(p.x, p.y, tin.height(v));
    }
    std::sort(out.begin(), out.end());
    return out;
}

struct Edit {
    const char* name;
    double (*terrain)(Vec2);
    std::size_t points;
    ToolSpec tool;
    std::vector<Vec2> path;  ///< one point: a single stamp
    double bottom;
    bool simplify;
    /// Same vertex positions, heights (and the surface) within this many metres; negative: only
    /// the looser agreement of a long stroke (see below).
    double same_vertices_within;
};

struct Outcome {
    std::vector<Vertex> vertices;
    double volume = 0.0;
    StampReport report;
    Tin tin;
};

Outcome run(const Edit& e, bool clear) {
    Outcome out{{}, 0.0, {}, Tin::random_points(test::kUnitSquare, e.points, 77, e.terrain)};
    Tin& tin = out.tin;
    SculptContext context(tin.domain());
    context.settings.simplify_after_edit = e.simplify;
    context.settings.clear_before_imprint = clear;
    context.settings.min_bulk_clearing = 0;  // these scenes are small: clear whatever qualifies
    const Tool tool = Tool::build(e.tool);
    if (e.path.size() == 1) {
        out.report = stamp(tin, tool, {e.path[0], 0.3, e.bottom}, context);
    } else {
        StrokeSettings s;
        s.depth_mode = DepthMode::Absolute;
        s.depth = e.bottom;
        s.spacing = 0.25 * e.tool.radius;
        out.report = apply_stroke(tin, tool, e.path, s, context);
    }
    const ValidationReport valid = tin.check_valid();
    EXPECT_TRUE(valid.ok()) << valid.summary();
    out.vertices = vertices_of(tin);
    out.volume = tin.volume();
    return out;
}

ToolSpec circle(double radius) {
    ToolSpec spec;
    spec.contour = ContourKind::Circle;
    spec.radius = radius;
    spec.control_points = 12;
    return spec;
}

TEST(StampClearing, GivesTheSameTerrainAsThePlainPath) {
    ToolSpec lambda = load_tool_asset("lambda");
    lambda.radius = 0.08;
    // One stamp, or a stroke on flat sand, leaves the same vertices at the same heights: to
    // rounding, or, where the floor meets sand below it, to about 10 micrometres (a fifth of
    // d_m is asserted): the simplifier removes the floor vertices there in another order, and
    // VolumePolicy::Conserve compensates each removal with a small shift of its neighbours. Over a
    // stroke on curved sand those shifts feed into later stamps; both terrains then agree
    // within the stamp's own tolerances, and on average far better.
    // clang-format off
    const std::vector<Edit> edits = {
        {"groove on dense flat sand", flat, 40000, circle(0.04), {{0.2, 0.2}, {0.8, 0.8}}, -0.1,
         true, 1e-15},
        {"lambda stamp on curved sand", test::wavy_sand, 20000, lambda, {{0.5, 0.5}}, 0.09, true, 1e-15},
        {"circle stamp, sand partly below the floor", test::wavy_sand, 20000, circle(0.06), {{0.4, 0.6}},
         0.1, true, 1e-4},
        {"stroke on curved sand, partly below the floor", test::wavy_sand, 20000, circle(0.05),
         {{0.2, 0.7}, {0.5, 0.4}, {0.8, 0.6}}, 0.1, true, -1.0},
        {"lambda stroke on curved sand", test::wavy_sand, 20000, lambda, {{0.3, 0.3}, {0.6, 0.5}}, 0.1,
         true, -1.0},
        {"stroke without simplification", test::wavy_sand, 10000, circle(0.05), {{0.3, 0.3}, {0.7, 0.4}},
         0.1, false, -1.0},
    };
    // clang-format on
    for (const Edit& e : edits) {
        SCOPED_TRACE(e.name);
        const Outcome plain = run(e, false);
        const Outcome cleared = run(e, true);
        ASSERT_TRUE(plain.report.applied);
        // The clearing did work (else this compares the plain path with itself).
        EXPECT_GT(cleared.report.cleared.removed, 0u);
        EXPECT_EQ(plain.report.cleared.removed, 0u);
        const double tolerance = std::max(Tool::build(e.tool).rim_tolerance(),
                                          default_simplify_tolerance(test::kUnitSquare));
        LocateHint h1, h2;
        double worst = 0.0;
        double sum = 0.0;
        const std::vector<Vec2> probes = test::random_points_in(test::kUnitSquare, 20000, 5);
        for (Vec2 p : probes) {
            const double d =
                std::abs(*cleared.tin.height_at(p, &h1) - *plain.tin.height_at(p, &h2));
            worst = std::max(worst, d);
            sum += d;
        }
        const double displaced = std::abs(plain.report.displaced_volume);
        ASSERT_GT(displaced, 0.0);
        const double within = e.same_vertices_within;
        if (within >= 0.0) {
            ASSERT_EQ(cleared.vertices.size(), plain.vertices.size());
            for (std::size_t i = 0; i < plain.vertices.size(); ++i) {
                const auto [x1, y1, z1] = plain.vertices[i];
                const auto [x2, y2, z2] = cleared.vertices[i];
                ASSERT_EQ(x1, x2);
                ASSERT_EQ(y1, y2);
                ASSERT_NEAR(z1, z2, within) << "at (" << x1 << ", " << y1 << ")";
            }
            EXPECT_LE(worst, within);
            EXPECT_NEAR(cleared.volume, plain.volume, within);
        } else {
            const double n = static_cast<double>(plain.vertices.size());
            EXPECT_LE(std::abs(static_cast<double>(cleared.vertices.size()) - n),
                      std::max(2.0, 1e-3 * n));
            EXPECT_LE(worst, tolerance);
            EXPECT_LE(sum / static_cast<double>(probes.size()), 1e-3 * tolerance);
            EXPECT_LE(std::abs(cleared.volume - plain.volume), 1e-4 * displaced);
        }
        EXPECT_NEAR(cleared.report.displaced_volume, plain.report.displaced_volume,
                    (within >= 0.0 ? 1e-6 : 1e-4) * displaced);
    }
}

}  // namespace
}  // namespace sandtin
