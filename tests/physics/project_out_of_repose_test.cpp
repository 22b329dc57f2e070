// The projection where the sand is out of repose (physics/project_out_of_repose): against the
// whole terrain's projection (the same answer where the region's rim did not move), with the
// sand outside the region untouched, the volume exact, no face left steep, a region too small
// for the settled pile grown until it fits, and a terrain at rest left alone for one pass.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/material.hpp"
#include "physics/project_out_of_repose.hpp"
#include "physics/settle_by_projection.hpp"
#include "tin/tin.hpp"
#include "tin/vertex_arrays.hpp"

namespace sandtin {
namespace {
namespace project_out_of_repose_test {

double volume_of(const ProjectionInput& in, const std::vector<double>& h) {
    double v = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        if (in.alive[i]) v += in.area[i] * h[i];
    }
    return v;
}

/// max |grad h| / bound over the input's faces, the bound as the projection's (tan(alpha)).
double steepest_ratio(const ProjectionInput& in, const std::vector<double>& h) {
    double worst = 0.0;
    for (std::size_t f = 0; f < in.faces.size(); ++f) {
        const auto& c = in.faces[f];
        const Vec2 e1 = in.position[c[1]] - in.position[c[0]];
        const Vec2 e2 = in.position[c[2]] - in.position[c[0]];
        const double det = cross(e1, e2);
        const double dz1 = h[c[1]] - h[c[0]], dz2 = h[c[2]] - h[c[0]];
        const Vec2 g{(dz1 * e2.y - dz2 * e1.y) / det, (e1.x * dz2 - e2.x * dz1) / det};
        worst = std::max(worst, length(g) / in.face_tan_alpha[f]);
    }
    return worst;
}

/// A 45-degree cone of height `height` at `apex` on a flat n x n lattice of the unit square
/// (a lattice: a random TIN's slivers stand steeper than the surface they sample).
Tin cone_on_lattice(int n, Vec2 apex, double height) {
    return Tin::regular_grid(
        Rect::from_size(1.0, 1.0), n, n,
        [&](Vec2 p) { return std::max(0.0, height - length(p - apex)); }, TinOptions{false});
}

TEST(ProjectOutOfRepose, AConeSettlesAsInTheWholeTerrainsProjectionTouchingOnlyItsNeighbourhood) {
    const Vec2 apex{0.3, 0.35};
    const Tin tin = cone_on_lattice(41, apex, 0.08);
    const ProjectionInput in = gather_projection_input(tin, MaterialTable::presets());
    OutOfReposeReport report;
    const ReposeProjection local = project_out_of_repose(in, {}, {}, &report);
    const ReposeProjection whole = project_onto_repose(in.problem());
    ASSERT_TRUE(local.converged);
    ASSERT_TRUE(whole.converged);
    EXPECT_GT(report.steep_faces, 0u);
    EXPECT_GE(report.rounds, 1);
    EXPECT_FALSE(report.whole_terrain);
    // The settled cone reaches 0.08 (tan 45 / tan 32)^(1/3) = 0.11 m from the apex: a small
    // part of the 1 764 vertices is free.
    EXPECT_LT(report.free_vertices, in.height.size() / 4) << report.free_vertices;
    // The same surface as the whole terrain's projection, to the solver's tolerance (each
    // stops at relative residuals of 1e-4; 0.5 % of the pile's height is far above that).
    double worst = 0.0;
    for (std::size_t v = 0; v < in.height.size(); ++v)
        worst = std::max(worst, std::abs(local.height[v] - whole.height[v]));
    EXPECT_LT(worst, 0.005 * 0.08) << worst;
    // Every face at rest, the volume exact, and sand beyond the settled pile untouched.
    EXPECT_LE(steepest_ratio(in, local.height), 1.0 + 1e-4);
    const double before = volume_of(in, in.height);
    EXPECT_NEAR(volume_of(in, local.height), before, 1e-12 * before);
    for (std::size_t v = 0; v < in.height.size(); ++v) {
        if (length(in.position[v] - apex) > 0.3) {
            EXPECT_EQ(local.height[v], in.height[v]) << v;
        }
    }
}

TEST(ProjectOutOfRepose, ARegionTooSmallForThePileGrowsUntilItFits) {
    // A spike of sand on one vertex of a flat lattice: the first rings (3, 7.5 cm) hold a
    // settled pile that wants about 12 cm; the sand reaches the rim, and the region grows.
    const Tin flat = cone_on_lattice(41, {0.5, 0.5}, 0.0);
    ProjectionInput in = gather_projection_input(flat, MaterialTable::presets());
    std::size_t centre = 0;
    for (std::size_t v = 0; v < in.height.size(); ++v) {
        if (length(in.position[v] - Vec2{0.5, 0.5}) < length(in.position[centre] - Vec2{0.5, 0.5}))
            centre = v;
    }
    in.height[centre] = 0.002 / in.area[centre];  // 2 litres
    OutOfReposeReport report;
    std::vector<double> heard;
    ReposeProjectionOptions options;
    options.on_progress = [&](double f) { heard.push_back(f); };
    const ReposeProjection local = project_out_of_repose(in, options, {}, &report);
    ASSERT_TRUE(local.converged);
    EXPECT_GE(report.rounds, 1);
    EXPECT_GT(report.rings, 3);  // grown from the first 3
    const ReposeProjection whole = project_onto_repose(in.problem());
    double worst = 0.0, top = 0.0;
    for (std::size_t v = 0; v < in.height.size(); ++v) {
        worst = std::max(worst, std::abs(local.height[v] - whole.height[v]));
        top = std::max(top, whole.height[v]);
    }
    EXPECT_LT(worst, 0.005 * top) << worst << " of " << top;
    EXPECT_LE(steepest_ratio(in, local.height), 1.0 + 1e-4);
    const double before = volume_of(in, in.height);
    EXPECT_NEAR(volume_of(in, local.height), before, 1e-12 * before);
    // One bar over every round: rising, ending at 1.
    ASSERT_FALSE(heard.empty());
    EXPECT_EQ(heard.back(), 1.0);
    for (std::size_t k = 1; k < heard.size(); ++k) {
        EXPECT_GE(heard[k], heard[k - 1]) << k;
    }
}

TEST(ProjectOutOfRepose, ATerrainAtRestIsLeftAloneInOnePass) {
    const Tin tin = Tin::regular_grid(
        Rect::from_size(1.0, 1.0), 30, 30,
        [](Vec2 p) { return 0.02 * std::sin(6.0 * p.x) * std::cos(5.0 * p.y); }, TinOptions{false});
    const ProjectionInput in = gather_projection_input(tin, MaterialTable::presets());
    ASSERT_LT(steepest_ratio(in, in.height), 1.0);
    OutOfReposeReport report;
    int calls = 0;
    ReposeProjectionOptions options;
    options.on_progress = [&](double f) {
        ++calls;
        EXPECT_EQ(f, 1.0);
    };
    const ReposeProjection r = project_out_of_repose(in, options, {}, &report);
    EXPECT_EQ(report.rounds, 0);
    EXPECT_EQ(report.steep_faces, 0u);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.height, in.height);
    EXPECT_EQ(calls, 1);
}

TEST(ProjectOutOfRepose, VerticesTheInputHoldsStayAndBadOptionsAreRefused) {
    const Vec2 apex{0.5, 0.5};
    const Tin tin = cone_on_lattice(41, apex, 0.1);
    ProjectionInput in = gather_projection_input(tin, MaterialTable::presets());
    // Hold a ring of vertices across the pile's future foot; the rest is free.
    in.held.assign(in.height.size(), 0);
    for (std::size_t v = 0; v < in.height.size(); ++v) {
        const double r = length(in.position[v] - apex);
        if (r > 0.12 && r < 0.14) in.held[v] = 1;
    }
    const ReposeProjection local = project_out_of_repose(in);
    for (std::size_t v = 0; v < in.height.size(); ++v) {
        if (in.held[v]) {
            EXPECT_EQ(local.height[v], in.height[v]) << v;
        }
    }
    const double before = volume_of(in, in.height);
    EXPECT_NEAR(volume_of(in, local.height), before, 1e-12 * before);
    OutOfReposeOptions no_rings;
    no_rings.first_rings = 0;
    EXPECT_THROW(project_out_of_repose(in, {}, no_rings), std::invalid_argument);
    ProjectionInput short_input = in;
    short_input.bedrock.pop_back();
    EXPECT_THROW(project_out_of_repose(short_input), std::invalid_argument);
}

}  // namespace project_out_of_repose_test
}  // namespace
}  // namespace sandtin
