// The regular-grid baseline under the face rule (issue 39 item 2): the 4-8 mesh's graph and
// lumped areas, exact volume, and a poured cone that rests with no face steeper than repose
// and approaches the analytic cone as the grid is refined.

#include <gtest/gtest.h>

#include <cmath>

#include "physics/cone.hpp"
#include "physics/face_slopes.hpp"
#include "physics/grid_erosion.hpp"
#include "physics/material.hpp"
#include "physics/repose_projection.hpp"

namespace sandtin {
namespace {

double grid_tan() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

TalusSettings face_settings() {
    TalusSettings settings;
    settings.parameters.rule = SlopeRule::Face;
    return settings;
}

TEST(GridFaceRule, LumpedAreasAreAThirdOfTheTrianglesAndSumToTheCentresRectangle) {
    const int nx = 7, ny = 5;
    const GridErosion grid(Rect::from_size(1.4, 0.5), nx, ny, grid_tan(), face_settings());
    const double cell = grid.cell_size_x() * grid.cell_size_y();
    double total = 0.0;
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            total += grid.area(i, j);
            const bool interior = i > 0 && j > 0 && i + 1 < nx && j + 1 < ny;
            // Inside, a centre on its quads' diagonals has 8 triangles, the others 4.
            if (interior) {
                EXPECT_NEAR(grid.area(i, j), ((i + j) % 2 == 0 ? 8 : 4) * cell / 6.0, 1e-15);
            }
        }
    }
    // The triangles cover the rectangle of the centres: (nx - 1) (ny - 1) cells.
    EXPECT_NEAR(total, (nx - 1) * (ny - 1) * cell, 1e-14);
    // The faces the judge sees are the same triangles: two per quad, covering it.
    const std::vector<SlopeFace> faces = grid.faces();
    EXPECT_EQ(faces.size(), 2u * (nx - 1) * (ny - 1));
    double covered = 0.0;
    for (const SlopeFace& f : faces)
        covered +=
            0.5 * std::abs((f.b.x - f.a.x) * (f.c.y - f.a.y) - (f.b.y - f.a.y) * (f.c.x - f.a.x));
    EXPECT_NEAR(covered, total, 1e-14);
}

TEST(GridFaceRule, HeightAtIsLinearOnTheTrianglesTheJudgeSees) {
    GridErosion grid(Rect::from_size(1.0, 1.0), 6, 6, grid_tan(), face_settings());
    for (int j = 0; j < 6; ++j) {
        for (int i = 0; i < 6; ++i)
            grid.height(i, j) = std::sin(3.0 * i + 1.7 * j);  // arbitrary, not planar
    }
    // At each face's centroid, height_at is the mean of the face's corners.
    for (const SlopeFace& f : grid.faces()) {
        const Vec2 centroid{(f.a.x + f.b.x + f.c.x) / 3.0, (f.a.y + f.b.y + f.c.y) / 3.0};
        EXPECT_NEAR(grid.height_at(centroid), (f.a.z + f.b.z + f.c.z) / 3.0, 1e-12);
    }
}

struct GridCone {
    double mean_error = 0.0;
    double volume_error = 0.0;
    FaceSlopeReport faces;
    bool at_rest = false;
};

GridCone pour_grid_cone(int n, double settle_margin) {
    constexpr double kVolume = 0.01;
    TalusSettings settings = face_settings();
    settings.parameters.settle_margin = settle_margin;
    GridErosion grid(Rect::from_size(1.0, 1.0), n, n, grid_tan(), settings);
    grid.pour({0.5, 0.5}, kVolume);
    GridCone out;
    out.volume_error = std::abs(grid.volume() - kVolume) / kVolume;
    out.at_rest = grid.run_to_rest(400000) < 400000 && grid.active_count() == 0;
    out.volume_error = std::max(out.volume_error, std::abs(grid.volume() - kVolume) / kVolume);
    const std::vector<SlopeFace> faces = grid.faces();
    out.faces = measure_face_slopes(faces);
    const int c = n / 2;
    const Vec2 apex = grid.centre(c, c);
    // Against the cone at (1 - m) tan(alpha): flowing faces level towards it.
    const Cone cone = Cone::from_volume(kVolume, (1.0 - settle_margin) * grid_tan());
    double sum = 0.0;
    constexpr int kSamples = 100;
    for (int j = 0; j < kSamples; ++j) {
        for (int i = 0; i < kSamples; ++i) {
            const Vec2 p{(i + 0.5) / kSamples, (j + 0.5) / kSamples};
            sum += std::abs(grid.height_at(p) - cone.surface(distance(p, apex)));
        }
    }
    out.mean_error = sum / (kSamples * kSamples);
    std::printf("  %d x %d: mean error %.3g m, steepest face %.5f, %zu steep\n", n, n,
                out.mean_error, out.faces.max_ratio, out.faces.steep_faces);
    return out;
}

TEST(GridFaceRule, APouredConeRestsWithNoFaceSteeperThanReposeAndItsVolume) {
    // Both the default margin and a small one. (Refinement does not yet bring the pile much
    // closer to the analytic cone: 3.6e-4 -> 3.3e-4 m from 32² to 64² at m = 0.005. The faces'
    // overshoot leaves the pile flatter than repose, an error floor: issue 39's open item.)
    for (const double margin : {TalusParameters{}.settle_margin, 0.005}) {
        for (const int n : {32, 64}) {
            const GridCone g = pour_grid_cone(n, margin);
            EXPECT_TRUE(g.at_rest) << n << ", m = " << margin;
            EXPECT_LT(g.volume_error, 1e-12);
            EXPECT_EQ(g.faces.steep_faces, 0u) << "steepest " << g.faces.max_ratio;
            // Within 1.5 % of the cone's height on average over the square (the cone covers
            // a fifth of it): a pile, not a smear.
            const Cone cone = Cone::from_volume(0.01, grid_tan());
            EXPECT_LT(g.mean_error, 0.015 * cone.height);
        }
    }
}

TEST(GridFaceRule, APourSettledByProjectionIsTheAnalyticConeWithItsVolume) {
    // The TIN's solver on the 4-8 mesh (settle_by_projection, where the sand is out of
    // repose): 10 L on one cell of a 64² grid becomes the cone of 10 L at repose.
    constexpr double kVolume = 0.01;
    GridErosion grid(Rect::from_size(1.0, 1.0), 64, 64, grid_tan(), face_settings());
    grid.pour({0.5, 0.5}, kVolume);
    const ReposeProjection p = grid.settle_by_projection();
    EXPECT_TRUE(p.converged);
    EXPECT_NEAR(grid.volume(), kVolume, 1e-12 * kVolume);
    const std::vector<SlopeFace> faces = grid.faces();
    EXPECT_LE(measure_face_slopes(faces).max_ratio, 1.0 + 1e-4);
    const Cone cone = Cone::from_volume(kVolume, grid_tan());
    const Vec2 apex = grid.centre(32, 32);
    double sum = 0.0;
    int count = 0;
    for (int j = 0; j < 100; ++j) {
        for (int i = 0; i < 100; ++i) {
            const Vec2 q{(i + 0.5) / 100, (j + 0.5) / 100};
            if (distance(q, apex) > 1.2 * cone.radius) continue;
            sum += std::abs(grid.height_at(q) - cone.surface(distance(q, apex)));
            ++count;
        }
    }
    // The mesh's 1.6 cm spacing against a cone 0.155 m high: within 1 % of it on average
    // (0.35 % measured; local moves on the same grid floor at 1.5 % over the square).
    EXPECT_LT(sum / count, 0.01 * cone.height) << sum / count;
}

TEST(GridEdgeRule, LeavesFacesSteeperThanReposeWhereTheFaceRuleLeavesNone) {
    // The oracle the face rule exists for: the seeds' edge rule on the 8-connected grid rests
    // with faces of the 4-8 mesh steeper than repose (bench erosion measured the steepest at
    // 1.14 tan(alpha) on this 32² cone).
    GridErosion grid(Rect::from_size(1.0, 1.0), 32, 32, grid_tan(), seeds_rule());
    grid.pour({0.5, 0.5}, 0.01);
    grid.run_to_rest(400000);
    const std::vector<SlopeFace> faces = grid.faces();
    EXPECT_GT(measure_face_slopes(faces).steep_faces, 0u);
}

TEST(GridFaceRule, AssignRefusesAcrossLengthsThatAreNegativeOrMissing) {
    const std::vector<std::vector<std::uint32_t>> rows = {{1, 2}, {2, 0}, {0, 1}};
    const std::vector<std::vector<double>> lengths = {{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}};
    AdjacencyGraph graph;
    const std::vector<std::vector<double>> good = {{1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}};
    graph.assign(rows, lengths, &good);
    EXPECT_EQ(graph.across()[graph.offset(0)], 1.0);
    const std::vector<std::vector<double>> negative = {{-1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}};
    EXPECT_THROW(graph.assign(rows, lengths, &negative), std::invalid_argument);
    const std::vector<std::vector<double>> short_row = {{1.0}, {1.0, 0.0}, {1.0, 0.0}};
    EXPECT_THROW(graph.assign(rows, lengths, &short_row), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin
