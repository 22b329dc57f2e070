// The per-face rest criterion (physics/face_slopes): the gradient of a plane through three
// points against its analytic value, and the report on terrains whose every face has a known
// slope (planes), with rock, regions, slivers and mixed materials.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "physics/face_slopes.hpp"
#include "physics/material.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

double dry_tan() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

TEST(FaceGradient, EqualsThePlanesGradientForAnyTriangleOnIt) {
    // z = 0.3 x - 0.4 y + 2: |∇h| = 0.5 for every non-degenerate triangle on it.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    auto z = [](double x, double y) { return 0.3 * x - 0.4 * y + 2.0; };
    for (int k = 0; k < 200; ++k) {
        Vec3 p[3];
        for (Vec3& q : p) {
            q.x = u(rng);
            q.y = u(rng);
            q.z = z(q.x, q.y);
        }
        EXPECT_NEAR(face_gradient(p[0], p[1], p[2]), 0.5, 1e-9) << k;
    }
}

TEST(FaceGradient, AThinTriangleIsSteeperThanAnyOfItsEdges) {
    // The cause: edges 1 m and ~0.5 m long rising at most 0.015 over their length,
    // but the face rises 7.5 mm over 1 cm across: 0.75, steeper than dry sand's 0.62.
    const Vec3 a{0.0, 0.0, 0.0}, b{1.0, 0.0, 0.0}, c{0.5, 0.01, 0.0075};
    const double edge_ac = (c.z - a.z) / std::hypot(c.x - a.x, c.y - a.y);
    const double edge_bc = (c.z - b.z) / std::hypot(c.x - b.x, c.y - b.y);
    EXPECT_LT(std::max(edge_ac, edge_bc), 0.016);
    EXPECT_NEAR(face_gradient(a, b, c), 0.75, 1e-12);
    EXPECT_GT(face_gradient(a, b, c), dry_tan());
}

TEST(FaceGradient, ADegenerateTriangleHasNoFiniteGradient) {
    EXPECT_EQ(face_gradient({0, 0, 0}, {1, 1, 1}, {2, 2, 5}),
              std::numeric_limits<double>::infinity());
}

Tin plane(double gradient) {
    // Rising along (3, 4) / 5 at `gradient` m/m.
    return Tin::random_points(Rect::from_size(1, 1), 3000, 17, [gradient](Vec2 p) {
        return 1.0 + gradient * (0.6 * p.x + 0.8 * p.y);
    });
}

TEST(FaceSlopes, APlaneGentlerThanReposeHasNoSteepFace) {
    const Tin tin = plane(0.9 * dry_tan());
    const FaceSlopeReport r = measure_face_slopes(tin, MaterialTable::presets());
    EXPECT_EQ(r.faces, tin.triangle_count());
    EXPECT_EQ(r.steep_faces, 0u);
    EXPECT_EQ(r.steep_area, 0.0);
    EXPECT_NEAR(r.area, 1.0, 1e-9);         // the unit square
    EXPECT_NEAR(r.sloped_area, 1.0, 1e-9);  // every face is on the slope
    EXPECT_NEAR(r.max_ratio, 0.9, 1e-6);
    EXPECT_EQ(r.rock_faces, 0u);
}

TEST(FaceSlopes, APlaneJustSteeperThanTheToleranceIsSteepEverywhere) {
    const Tin tin = plane(1.002 * dry_tan());
    const FaceSlopeReport r = measure_face_slopes(tin, MaterialTable::presets());
    EXPECT_EQ(r.steep_faces, r.faces);
    EXPECT_NEAR(r.steep_share_of_slopes(), 1.0, 1e-12);
    EXPECT_NEAR(r.max_ratio, 1.002, 1e-6);
    // Inside the tolerance it is not steep.
    FaceSlopeOptions lenient;
    lenient.tolerance = 3e-3;
    EXPECT_EQ(measure_face_slopes(tin, MaterialTable::presets(), lenient).steep_faces, 0u);
}

TEST(FaceSlopes, TheRegionKeepsOnlyFacesWhoseCentroidLiesInside) {
    const Tin tin = plane(0.5);
    FaceSlopeOptions left;
    left.region = Rect{{0.0, 0.0}, {0.5, 1.0}};
    FaceSlopeOptions right;
    right.region = Rect{{0.5, 0.0}, {1.0, 1.0}};
    const FaceSlopeReport l = measure_face_slopes(tin, MaterialTable::presets(), left);
    const FaceSlopeReport r = measure_face_slopes(tin, MaterialTable::presets(), right);
    // A centroid on x = 0.5 exactly would count twice; random points put none there.
    EXPECT_EQ(l.faces + r.faces, tin.triangle_count());
    EXPECT_NEAR(l.area + r.area, 1.0, 1e-9);
    EXPECT_NEAR(l.area, 0.5, 0.02);
}

TEST(FaceSlopes, RockIsNotJudged) {
    Tin tin = plane(2.0 * dry_tan());
    const VertexArrays& va = tin.vertices();
    // Sand everywhere but the left half, where the surface is bare bedrock.
    std::size_t left_faces = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        const VertexId id{v};
        tin.set_bedrock(id, va.position[v].x < 0.5 ? va.height[v] : va.height[v] - 0.1);
    }
    for (const auto& t : tin.triangles()) {
        bool all_left = true;
        for (VertexId v : t)
            all_left = all_left && va.position[v.value].x < 0.5;
        left_faces += all_left ? 1 : 0;
    }
    const FaceSlopeReport r = measure_face_slopes(tin, MaterialTable::presets());
    EXPECT_EQ(r.rock_faces, left_faces);
    EXPECT_EQ(r.faces, tin.triangle_count() - left_faces);
    EXPECT_EQ(r.steep_faces, r.faces);  // the sand half is twice too steep
}

TEST(FaceSlopes, AFacesAngleIsTheMeanOfItsCorners) {
    // Two triangles, one gradient; corners of dry sand (32°) and gravel (preset 2).
    Tin tin = Tin::flat_rectangle(Rect::from_size(1, 1), 0.0);
    const MaterialTable m = MaterialTable::presets();
    const double tan_dry = m.at(0).talus_slope(0.0), tan_gravel = m.at(2).talus_slope(0.0);
    ASSERT_NE(tan_dry, tan_gravel);
    const double g = 0.5 * (tan_dry + tan_gravel);
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> corners;
    for (std::uint32_t v = 0; v < va.size(); ++v)
        if (va.alive[v]) corners.push_back(VertexId{v});
    ASSERT_EQ(corners.size(), 4u);
    for (VertexId v : corners)
        tin.set_height(v, g * va.position[v.value].x);
    // All dry: steeper than dry sand if g > tan_dry.
    const FaceSlopeReport dry = measure_face_slopes(tin, m);
    EXPECT_NEAR(dry.max_ratio, g / tan_dry, 1e-12);
    // All gravel: the ratio follows gravel's angle.
    for (VertexId v : corners)
        tin.set_material(v, 2);
    EXPECT_NEAR(measure_face_slopes(tin, m).max_ratio, g / tan_gravel, 1e-12);
    // One dry corner among gravel: the face that has it takes the mean of its three corners'
    // angles, the gentlest of any face here, so the largest ratio is that face's.
    ASSERT_GT(tan_gravel, tan_dry);
    const auto faces = tin.triangles();
    ASSERT_EQ(faces.size(), 2u);
    tin.set_material(faces[0][0], 0);
    const double mean_one_dry = (tan_dry + 2.0 * tan_gravel) / 3.0;
    EXPECT_NEAR(measure_face_slopes(tin, m).max_ratio, g / mean_one_dry, 1e-12);
}

TEST(FaceSlopes, SliversBelowTheAreaFractionAreSkippedAndCounted) {
    const Tin tin = plane(0.3);
    FaceSlopeOptions strict;
    strict.min_area_fraction = 0.0;
    const FaceSlopeReport all = measure_face_slopes(tin, MaterialTable::presets(), strict);
    EXPECT_EQ(all.skipped_faces, 0u);
    // Skip faces under the median face's share: about half are skipped, and counted.
    FaceSlopeOptions coarse;
    coarse.min_area_fraction = 1.0 / static_cast<double>(tin.triangle_count());
    const FaceSlopeReport some = measure_face_slopes(tin, MaterialTable::presets(), coarse);
    EXPECT_GT(some.skipped_faces, 0u);
    EXPECT_EQ(some.faces + some.skipped_faces, all.faces);
    EXPECT_LT(some.area, all.area);
}

TEST(FaceSlopes, RejectsBadOptions) {
    const Tin tin = plane(0.3);
    FaceSlopeOptions bad;
    bad.tolerance = -1.0;
    EXPECT_THROW(measure_face_slopes(tin, MaterialTable::presets(), bad), std::invalid_argument);
    bad = {};
    bad.min_area_fraction = std::nan("");
    EXPECT_THROW(measure_face_slopes(tin, MaterialTable::presets(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace sandtin
