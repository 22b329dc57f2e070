// Decimation after greedy insertion: fewer points for the same bound, the bound checked by an
// independent oracle, and the holes filled exactly as CGAL triangulates the points left.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>

#include "io/greedy_decimation.hpp"
#include "io/greedy_tin.hpp"
#include "io/lattice_delaunay.hpp"
#include "support/height_fields.hpp"
#include "support/lattice_triangles.hpp"
#include "support/raster_oracle.hpp"
#include "support/tin_oracles.hpp"

namespace sandtin {
namespace {

using test::LatticeTriple;

/// A hash of a sample in [-1, 1]: the raster's roughness, the same on every platform.
double sample_noise(std::uint32_t col, std::uint32_t row, std::uint64_t seed) {
    std::uint64_t h =
        (static_cast<std::uint64_t>(col) << 32 | row) ^ (seed * 0x9E3779B97F4A7C15ull);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return static_cast<double>(h >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

/// Smooth hills with rough detail on top (cell 1 m): where greedy insertion over-inserts.
HeightRaster rough_raster(std::uint32_t w, std::uint32_t h, double roughness, std::uint64_t seed) {
    return test::raster_of(w, h, [&](double x, double y) {
        return 8.0 * std::sin(0.07 * x + 0.3) * std::cos(0.05 * y) +
               3.0 * std::sin(0.21 * x + 0.17 * y) +
               roughness *
                   sample_noise(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), seed);
    });
}

std::set<LatticeTriple> triangles_of_mesh(const LatticeMesh& mesh) {
    std::set<LatticeTriple> out;
    for (const auto& t : mesh.triangles) {
        LatticeTriple tri;
        for (std::size_t k = 0; k < 3; ++k)
            tri[k] = {mesh.points[t[k]].x, mesh.points[t[k]].y};
        out.insert(test::rotated_to_smallest(tri));
    }
    return out;
}

/// The lattice triangulation of a TIN whose vertices lie on samples, built by inserting them
/// one by one into LatticeDelaunay (the triangle found by brute force).
LatticeMesh lattice_mesh_of(const Tin& tin, std::int32_t w, std::int32_t h) {
    LatticeDelaunay dt(w, h);
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 q = tin.position(v);
        const LatticePoint p{static_cast<std::int32_t>(std::llround(q.x)),
                             static_cast<std::int32_t>(std::llround(q.y))};
        if ((p.x == 0 || p.x == w) && (p.y == 0 || p.y == h)) continue;  // the corners
        for (std::uint32_t t = 0; t < dt.triangle_count(); ++t) {
            const auto c = dt.triangle(t);
            if (LatticeDelaunay::orient(dt.point(c[0]), dt.point(c[1]), p) >= 0 &&
                LatticeDelaunay::orient(dt.point(c[1]), dt.point(c[2]), p) >= 0 &&
                LatticeDelaunay::orient(dt.point(c[2]), dt.point(c[0]), p) >= 0) {
                std::vector<std::uint32_t> changed;
                dt.insert(p, t, changed);
                break;
            }
        }
    }
    LatticeMesh mesh;
    for (std::uint32_t v = 0; v < dt.point_count(); ++v)
        mesh.points.push_back(dt.point(v));
    for (std::uint32_t t = 0; t < dt.triangle_count(); ++t)
        mesh.triangles.push_back(dt.triangle(t));
    return mesh;
}

Tin tin_of_mesh(const LatticeMesh& mesh, const HeightRaster& r) {
    std::vector<Vec2> positions;
    std::vector<double> heights;
    for (const LatticePoint& p : mesh.points) {
        const auto col = static_cast<std::uint32_t>(p.x);
        const auto row = r.height - 1 - static_cast<std::uint32_t>(p.y);
        positions.push_back(r.position(col, row));
        heights.push_back(r.at(col, row));
    }
    return Tin::from_points(r.domain(), positions, heights);
}

// The holes are filled from their links alone, with CGAL's perturbed in-circle test: the mesh
// left must be the very triangulation CGAL builds for its points, cocircular lattice points
// and collinear border points included. Small rasters and coarse bounds make most holes
// large and most fills ambiguous without the perturbation.
TEST(GreedyDecimation, TheMeshLeftIsTheTriangulationCgalBuildsForItsPoints) {
    std::size_t removed_in_all = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        const std::uint32_t w = 14 + static_cast<std::uint32_t>(seed % 3) * 9;
        const std::uint32_t h = 11 + static_cast<std::uint32_t>(seed % 4) * 6;
        const HeightRaster r = rough_raster(w, h, 0.6 + 0.2 * static_cast<double>(seed % 3), seed);
        const double bound = 0.5;
        GreedyOptions plain{bound, 0};
        plain.decimate = false;
        const GreedyResult g = greedy_tin(r, plain);
        LatticeMesh mesh = lattice_mesh_of(g.tin, static_cast<std::int32_t>(w - 1),
                                           static_cast<std::int32_t>(h - 1));
        ASSERT_EQ(triangles_of_mesh(mesh), test::lattice_triples(g.tin)) << "seed " << seed;
        const std::size_t before = mesh.points.size();
        const DecimationStats stats = decimate_within_bound(mesh, r, bound);
        EXPECT_EQ(stats.removed, before - mesh.points.size());
        removed_in_all += stats.removed;
        const Tin left = tin_of_mesh(mesh, r);
        EXPECT_EQ(triangles_of_mesh(mesh), test::lattice_triples(left)) << "seed " << seed;
        EXPECT_LE(test::check_tin_against_raster(left, test::oracle_raster_of(r)).max_error,
                  bound + 1e-9)
            << "seed " << seed;
    }
    // Not a vacuous check: the rough rasters leave greedy insertion points to spare.
    EXPECT_GT(removed_in_all, 0u);
}

// End to end: on rough terrain the import keeps fewer points than greedy insertion alone, every
// sample is within the bound (measured by the oracle, not by the importer), the TIN CGAL
// builds needs no fix-up, and every vertex is still a raster sample at its own height.
TEST(GreedyDecimation, RoughTerrainNeedsFewerPointsForTheSameBound) {
    const HeightRaster r = rough_raster(150, 120, 1.5, 7);
    for (const double bound : {0.4, 1.0}) {
        GreedyOptions plain{bound, 0};
        plain.decimate = false;
        const GreedyResult without = greedy_tin(r, plain);
        const GreedyResult with = greedy_tin(r, {bound, 0});
        EXPECT_LT(with.tin.vertex_count(), without.tin.vertex_count()) << "bound " << bound;
        EXPECT_EQ(with.stats.decimated_points + with.tin.vertex_count(), without.tin.vertex_count())
            << "bound " << bound;
        EXPECT_EQ(without.stats.decimated_points, 0u);
        EXPECT_EQ(with.stats.fix_up_points, 0u);
        EXPECT_TRUE(with.stats.reached_error);
        const test::RasterCheck check =
            test::check_tin_against_raster(with.tin, test::oracle_raster_of(r));
        EXPECT_EQ(check.uncovered, 0u);
        EXPECT_LE(check.max_error, bound + 1e-9) << "bound " << bound;
        EXPECT_NEAR(with.stats.max_error, check.max_error, 1e-9);
        for (VertexId v : test::live_ids(with.tin)) {
            const Vec2 p = with.tin.position(v);
            ASSERT_EQ(p.x, std::round(p.x));
            ASSERT_EQ(p.y, std::round(p.y));
            EXPECT_EQ(with.tin.height(v), r.at(static_cast<std::uint32_t>(p.x),
                                               r.height - 1 - static_cast<std::uint32_t>(p.y)));
        }
        EXPECT_TRUE(with.tin.check_valid().ok()) << with.tin.check_valid().summary();
    }
}

// No-data samples carry no error: holes over them may close, but every valid sample stays
// within the bound and no vertex lands on a no-data sample.
TEST(GreedyDecimation, NoDataSamplesStayOutOfTheBoundAndOffTheVertices) {
    HeightRaster r = rough_raster(90, 70, 1.0, 3);
    r.valid.assign(r.size(), 1);
    for (std::uint32_t row = 20; row < 45; ++row) {
        for (std::uint32_t col = 30; col < 70; ++col) {
            r.valid[r.index(col, row)] = 0;
            r.heights[r.index(col, row)] = 0.0;
        }
    }
    const double bound = 0.5;
    const GreedyResult g = greedy_tin(r, {bound, 0});
    EXPECT_GT(g.stats.decimated_points, 0u);
    EXPECT_LE(test::check_tin_against_raster(g.tin, test::oracle_raster_of(r)).max_error,
              bound + 1e-9);
    for (VertexId v : test::live_ids(g.tin)) {
        const Vec2 p = g.tin.position(v);
        const std::size_t k = r.index(static_cast<std::uint32_t>(p.x),
                                      r.height - 1 - static_cast<std::uint32_t>(p.y));
        const bool corner = (p.x == 0.0 || p.x == 89.0) && (p.y == 0.0 || p.y == 69.0);
        EXPECT_TRUE(corner || r.valid[k])
            << "a vertex on a no-data sample at " << p.x << ", " << p.y;
    }
}

}  // namespace
}  // namespace sandtin
