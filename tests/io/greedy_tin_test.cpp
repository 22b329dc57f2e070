// Greedy insertion (Garland & Heckbert): the error bound against every raster sample, checked
// by an independent oracle; the point budget against delatin; the lattice triangulation
// against CGAL's.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "io/greedy_tin.hpp"
#include "io/heightmap_import.hpp"
#include "io/lattice_delaunay.hpp"
#include "io/lattice_raster.hpp"
#include "support/height_fields.hpp"
#include "support/lattice_triangles.hpp"
#include "support/raster_oracle.hpp"
#include "support/tin_oracles.hpp"

namespace sandtin {
namespace {

const std::string kTile = std::string(SANDTIN_TEST_DATA_DIR) + "/bay-hills-terrain-rgb.png";

using test::raster_of;

class BayHills : public ::testing::TestWithParam<std::pair<double, std::size_t>> {};

TEST_P(BayHills, EveryRasterSampleIsWithinTheBoundAndPointsDoNotExceedDelatin) {
    const auto [max_error, delatin_points] = GetParam();
    const ImportResult result = import_heightmap(kTile, {{}, {max_error, 0}});
    const Tin& tin = result.tin;
    // The oracle decodes the tile itself (libpng's simplified API, the Terrain-RGB formula).
    const test::OracleRaster raster = test::read_terrain_rgb(kTile);
    ASSERT_EQ(raster.width, 512u);
    ASSERT_EQ(raster.height, 512u);
    const test::RasterCheck check = test::check_tin_against_raster(tin, raster);
    EXPECT_EQ(check.samples, 512u * 512u);
    EXPECT_EQ(check.uncovered, 0u);
    EXPECT_LE(check.max_error, max_error + 1e-9);
    EXPECT_LE(tin.vertex_count(), delatin_points) << "more points than delatin needs";
    EXPECT_TRUE(result.report.stats.reached_error);
    EXPECT_EQ(result.report.stats.points, tin.vertex_count());
    EXPECT_EQ(result.report.stats.triangles, tin.triangle_count());
    EXPECT_NEAR(result.report.stats.max_error, check.max_error, 1e-9);
    // The lattice pass and the TIN agree (same cocircular tie-breaks): nothing to fix up.
    EXPECT_EQ(result.report.stats.fix_up_points, 0u);
    // Every vertex sits on a sample, at that sample's height.
    for (VertexId v : test::live_ids(tin)) {
        const Vec2 p = tin.position(v);
        ASSERT_EQ(p.x, std::round(p.x));
        ASSERT_EQ(p.y, std::round(p.y));
        const auto row = static_cast<std::uint32_t>(511 - p.y);
        EXPECT_EQ(tin.height(v), raster.at(static_cast<std::uint32_t>(p.x), row));
    }
    EXPECT_TRUE(tin.check_valid().ok()) << tin.check_valid().summary();
    EXPECT_EQ(test::join(test::mesh_problems(tin)), "");
}

// delatin 0.2.0's point counts for this tile (../shared/data/README.md).
INSTANTIATE_TEST_SUITE_P(Greedy, BayHills,
                         ::testing::Values(std::make_pair(10.0, std::size_t{190}),
                                           std::make_pair(0.2, std::size_t{16257})));

TEST(GreedyTin, RmsdMatchesAnIndependentSum) {
    const HeightRaster r = raster_of(40, 30, [](double x, double y) {
        return std::sin(x * 0.3) * 3.0 + std::cos(y * 0.2) * 2.0;
    });
    const GreedyResult g = greedy_tin(r, {0.25, 0});
    long double sum = 0.0L;
    for (std::uint32_t row = 0; row < r.height; ++row) {
        for (std::uint32_t col = 0; col < r.width; ++col) {
            const double z = test::brute_force_height(g.tin, r.position(col, row));
            sum += std::pow(static_cast<long double>(z - r.at(col, row)), 2);
        }
    }
    EXPECT_NEAR(g.stats.rmsd, std::sqrt(static_cast<double>(sum / r.size())), 1e-9);
    EXPECT_EQ(g.stats.samples, r.size());
    EXPECT_LE(test::check_tin_against_raster(g.tin, test::oracle_raster_of(r)).max_error,
              0.25 + 1e-9);
}

TEST(GreedyTin, APlaneNeedsOnlyTheCorners) {
    const HeightRaster r =
        raster_of(64, 33, [](double x, double y) { return 0.5 * x - 0.25 * y + 7; });
    const GreedyResult g = greedy_tin(r, {0.0, 0});
    EXPECT_EQ(g.tin.vertex_count(), 4u);
    EXPECT_EQ(g.tin.triangle_count(), 2u);
    EXPECT_LE(g.stats.max_error, 1e-12);
    EXPECT_EQ(g.tin.domain(), (Rect{{0, 0}, {63, 32}}));
}

TEST(GreedyTin, ZeroErrorReproducesTheRasterExactly) {
    const HeightRaster r = raster_of(17, 12, [](double x, double y) {
        return std::floor(std::sin(x) * 5.0) + std::floor(std::cos(y * 1.3) * 3.0);
    });
    const GreedyResult g = greedy_tin(r, {0.0, 0});
    EXPECT_LE(test::check_tin_against_raster(g.tin, test::oracle_raster_of(r)).max_error, 1e-9);
}

TEST(GreedyTin, StopsAtThePointLimit) {
    const ImportResult result = import_heightmap(kTile, {{}, {0.2, 500}});
    EXPECT_EQ(result.tin.vertex_count(), 500u);
    EXPECT_FALSE(result.report.stats.reached_error);
    EXPECT_GT(result.report.stats.max_error, 0.2);
    // The reported error is the measured one.
    const test::RasterCheck check =
        test::check_tin_against_raster(result.tin, test::read_terrain_rgb(kTile));
    EXPECT_NEAR(result.report.stats.max_error, check.max_error, 1e-9);
}

TEST(GreedyTin, NoDataSamplesAreIgnoredAndNeverBecomeVertices) {
    HeightRaster r =
        raster_of(50, 40, [](double x, double y) { return std::sin(x * 0.2) * y * 0.1; });
    r.valid.assign(r.size(), 1);
    // A block of garbage marked no-data, touching a corner.
    for (std::uint32_t row = 0; row < 15; ++row) {
        for (std::uint32_t col = 0; col < 12; ++col) {
            r.valid[r.index(col, row)] = 0;
            r.heights[r.index(col, row)] = 1e6;
        }
    }
    HeightRaster filled = r;
    EXPECT_EQ(fill_nodata(filled), 15u * 12u);
    const GreedyResult g = greedy_tin(filled, {0.05, 0});
    const test::RasterCheck check =
        test::check_tin_against_raster(g.tin, test::oracle_raster_of(r));
    EXPECT_LE(check.max_error, 0.05 + 1e-9);
    EXPECT_EQ(check.samples, r.size() - 15u * 12u);
    for (VertexId v : test::live_ids(g.tin)) {
        const Vec2 p = g.tin.position(v);
        const auto col = static_cast<std::uint32_t>(p.x);
        const auto row = static_cast<std::uint32_t>(39 - p.y);
        const bool corner = (col == 0 || col == 49) && (row == 0 || row == 39);
        EXPECT_TRUE(corner || r.valid[r.index(col, row)]) << "vertex on a no-data sample";
        EXPECT_LT(std::abs(g.tin.height(v)), 1e3) << "a no-data height leaked into the TIN";
    }
}

TEST(GreedyTin, NonSquareCellsStillMeetTheBound) {
    HeightRaster r =
        raster_of(30, 25, [](double x, double y) { return std::sin(x * 0.4) + y * 0.05; });
    r.cell_size = 0.5;
    r.cell_height = 0.8;
    for (std::uint32_t row = 0; row < r.height; ++row) {
        for (std::uint32_t col = 0; col < r.width; ++col) {
            const Vec2 p = r.position(col, row);
            r.heights[r.index(col, row)] = std::sin(p.x * 2.0) * std::cos(p.y);
        }
    }
    const GreedyResult g = greedy_tin(r, {0.02, 0});
    EXPECT_EQ(g.tin.domain(), r.domain());
    EXPECT_EQ(g.tin.domain().max.x, 14.5);
    // Check in metres: the oracle takes square cells, so scale y positions through a
    // brute-force height query instead.
    double worst = 0.0;
    for (std::uint32_t row = 0; row < r.height; ++row) {
        for (std::uint32_t col = 0; col < r.width; ++col) {
            worst = std::max(worst, std::abs(test::brute_force_height(g.tin, r.position(col, row)) -
                                             r.at(col, row)));
        }
    }
    EXPECT_LE(worst, 0.02 + 1e-9);
    EXPECT_TRUE(g.stats.reached_error);
}

TEST(GreedyTin, RejectsBadOptions) {
    const HeightRaster r = raster_of(4, 4, [](double, double) { return 0.0; });
    EXPECT_THROW(greedy_tin(r, {-1.0, 0}), std::invalid_argument);
    EXPECT_THROW(greedy_tin(r, {std::nan(""), 0}), std::invalid_argument);
    EXPECT_THROW(greedy_tin(r, {1.0, 3}), std::invalid_argument);
    HeightRaster bad = r;
    bad.heights[5] = std::numeric_limits<double>::infinity();
    EXPECT_THROW(greedy_tin(bad, {1.0, 0}), std::runtime_error);
}

TEST(LatticeRaster, SpansHoldExactlyTheLatticePointsOfTheClosedTriangle) {
    std::mt19937_64 rng = test::test_rng(7);
    for (int k = 0; k < 2000; ++k) {
        std::array<std::int64_t, 3> x{};
        std::array<std::int64_t, 3> y{};
        for (std::size_t c = 0; c < 3; ++c) {
            x[c] = static_cast<std::int64_t>(rng() % 23) - 5;
            y[c] = static_cast<std::int64_t>(rng() % 19) - 4;
        }
        const std::int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (area == 0) continue;
        if (area < 0) {
            std::swap(x[1], x[2]);
            std::swap(y[1], y[2]);
        }
        std::set<std::pair<std::int64_t, std::int64_t>> spans;
        for_each_lattice_span(x, y, [&](std::int64_t j, std::int64_t lo, std::int64_t hi) {
            for (std::int64_t i = lo; i <= hi; ++i)
                EXPECT_TRUE(spans.insert({i, j}).second) << "a point listed twice";
        });
        std::set<std::pair<std::int64_t, std::int64_t>> brute;
        for (std::int64_t j = -5; j <= 20; ++j) {
            for (std::int64_t i = -6; i <= 24; ++i) {
                bool inside = true;
                for (std::size_t c = 0; c < 3; ++c) {
                    const std::size_t d = (c + 1) % 3;
                    inside = inside && (x[d] - x[c]) * (j - y[c]) - (y[d] - y[c]) * (i - x[c]) >= 0;
                }
                if (inside) brute.insert({i, j});
            }
        }
        ASSERT_EQ(spans, brute) << "triangle " << k;
    }
}

// ---- The lattice triangulation is CGAL's, cocircular ties included --------------------------

using test::LatticeTriple;

std::set<LatticeTriple> lattice_triangles(const LatticeDelaunay& dt) {
    std::set<LatticeTriple> out;
    for (std::uint32_t t = 0; t < dt.triangle_count(); ++t) {
        LatticeTriple tri;
        const auto v = dt.triangle(t);
        for (std::size_t k = 0; k < 3; ++k)
            tri[k] = {dt.point(v[k]).x, dt.point(v[k]).y};
        out.insert(test::rotated_to_smallest(tri));
    }
    return out;
}

/// Inserts points by locating their triangle by brute force (the greedy always knows it).
void insert(LatticeDelaunay& dt, LatticePoint p) {
    for (std::uint32_t t = 0; t < dt.triangle_count(); ++t) {
        const auto v = dt.triangle(t);
        const LatticePoint a = dt.point(v[0]);
        const LatticePoint b = dt.point(v[1]);
        const LatticePoint c = dt.point(v[2]);
        if (LatticeDelaunay::orient(a, b, p) >= 0 && LatticeDelaunay::orient(b, c, p) >= 0 &&
            LatticeDelaunay::orient(c, a, p) >= 0) {
            std::vector<std::uint32_t> changed;
            dt.insert(p, t, changed);
            return;
        }
    }
    FAIL() << "no triangle contains the point";
}

TEST(LatticeDelaunay, EqualsCgalOnCocircularLatticePoints) {
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        std::mt19937_64 rng = test::test_rng(seed);
        // Small lattices are full of cocircular quadruples and collinear border points.
        const std::int32_t w = 3 + static_cast<std::int32_t>(seed % 5) * 2;
        const std::int32_t h = 2 + static_cast<std::int32_t>(seed % 4) * 3;
        std::vector<LatticePoint> all;
        for (std::int32_t y = 0; y <= h; ++y) {
            for (std::int32_t x = 0; x <= w; ++x) {
                if ((x == 0 || x == w) && (y == 0 || y == h)) continue;
                all.push_back({x, y});
            }
        }
        std::shuffle(all.begin(), all.end(), rng);
        all.resize(all.size() * (seed % 3 + 1) / 3);
        LatticeDelaunay dt(w, h);
        std::vector<Vec2> positions = {
            {0, 0}, {double(w), 0}, {double(w), double(h)}, {0, double(h)}};
        for (const LatticePoint p : all) {
            insert(dt, p);
            positions.push_back({double(p.x), double(p.y)});
        }
        const std::vector<double> heights(positions.size(), 0.0);
        const Tin tin = Tin::from_points(Rect{{0, 0}, {double(w), double(h)}}, positions, heights);
        EXPECT_EQ(lattice_triangles(dt), test::lattice_triples(tin)) << "seed " << seed;
    }
}

TEST(LatticeDelaunay, TrianglesAreCounterClockwiseAndLocallyDelaunay) {
    LatticeDelaunay dt(40, 30);
    std::mt19937_64 rng = test::test_rng(99);
    std::set<std::pair<int, int>> used = {{0, 0}, {40, 0}, {40, 30}, {0, 30}};
    for (int k = 0; k < 300; ++k) {
        const LatticePoint p{static_cast<std::int32_t>(rng() % 41),
                             static_cast<std::int32_t>(rng() % 31)};
        if (!used.insert({p.x, p.y}).second) continue;
        insert(dt, p);
    }
    // Every edge shared by two triangles passes the perturbed in-circle test from both sides;
    // areas tile the rectangle.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> opposite;
    std::int64_t area = 0;
    for (std::uint32_t t = 0; t < dt.triangle_count(); ++t) {
        const auto v = dt.triangle(t);
        const std::int64_t a2 =
            LatticeDelaunay::orient(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]));
        ASSERT_GT(a2, 0) << "triangle " << t << " is not counter-clockwise";
        area += a2;
        for (std::size_t k = 0; k < 3; ++k)
            opposite[{v[k], v[(k + 1) % 3]}] = v[(k + 2) % 3];
    }
    EXPECT_EQ(area, 2 * 40 * 30);
    for (const auto& [e, far] : opposite) {
        const auto twin = opposite.find({e.second, e.first});
        if (twin == opposite.end()) continue;
        EXPECT_LT(LatticeDelaunay::perturbed_in_circle(dt.point(e.first), dt.point(e.second),
                                                       dt.point(far), dt.point(twin->second)),
                  0);
    }
}

// The in-circle test decides most cases with a floating-point filter before its exact
// arithmetic. Its formula must agree with the exact determinant's sign at every scale, down to
// the nearest non-cocircular lattice cases: three points of a circle of radius up to 2^22
// around a lattice centre and a fourth one lattice step off it (squared distance r^2 +- 1), where
// the determinant is about 1e-13 of its terms' size. The sign is checked against a 128-bit
// determinant written out here.
TEST(LatticeDelaunay, InCircleAgreesWithExactArithmeticOnHugeNearCocircularPoints) {
    __extension__ using Wide = __int128;
    std::mt19937_64 rng = test::test_rng(4242);
    const std::int64_t limit = LatticeDelaunay::kMaxCoordinate;
    int decided_by_size = 0;
    for (int k = 0; k < 20000; ++k) {
        // A circle with a centre and radius on the lattice, its points from Pythagorean-like
        // offsets (r, 0), (0, r), (-r, 0), then the fourth moved off by one step.
        const std::int64_t r = 1 + static_cast<std::int64_t>(rng() % (limit / 4));
        const std::int64_t cx = r + static_cast<std::int64_t>(rng() % (limit - 2 * r));
        const std::int64_t cy = r + static_cast<std::int64_t>(rng() % (limit - 2 * r));
        const auto at = [](std::int64_t x, std::int64_t y) {
            return LatticePoint{static_cast<std::int32_t>(x), static_cast<std::int32_t>(y)};
        };
        const LatticePoint a = at(cx + r, cy);
        const LatticePoint b = at(cx, cy + r);
        const LatticePoint c = at(cx - r, cy);
        const std::int64_t dx = static_cast<std::int64_t>(rng() % 3) - 1;
        const std::int64_t dy = static_cast<std::int64_t>(rng() % 3) - 1;
        const LatticePoint d = at(cx + dx, std::max<std::int64_t>(0, cy - r + dy));
        const Wide ax = a.x - d.x, ay = a.y - d.y, bx = b.x - d.x, by = b.y - d.y;
        const Wide ex = c.x - d.x, ey = c.y - d.y;
        const Wide det = (ax * ax + ay * ay) * (bx * ey - by * ex) -
                         (bx * bx + by * by) * (ax * ey - ay * ex) +
                         (ex * ex + ey * ey) * (ax * by - ay * bx);
        if (det == 0) continue;  // cocircular: the perturbation decides (tested above)
        ++decided_by_size;
        ASSERT_EQ(LatticeDelaunay::perturbed_in_circle(a, b, c, d), det > 0 ? 1 : -1)
            << "radius " << r << " centre " << cx << ", " << cy << " offset " << dx << ", " << dy;
    }
    EXPECT_GT(decided_by_size, 10000);
}

TEST(LatticeDelaunay, PerturbedInCircleIsAntisymmetricAcrossAnEdge) {
    // For cocircular quadruples the decision must not depend on which side asks.
    const std::vector<std::array<LatticePoint, 4>> quads = {{{{0, 0}, {2, 0}, {2, 2}, {0, 2}}},
                                                            {{{0, 0}, {3, 1}, {2, 4}, {-1, 3}}},
                                                            {{{1, 0}, {2, 1}, {1, 2}, {0, 1}}},
                                                            {{{0, 0}, {4, 0}, {4, 3}, {0, 3}}}};
    for (const auto& q : quads) {
        for (int r = 0; r < 4; ++r) {
            const LatticePoint a = q[static_cast<std::size_t>(r)];
            const LatticePoint b = q[static_cast<std::size_t>((r + 1) % 4)];
            const LatticePoint c = q[static_cast<std::size_t>((r + 2) % 4)];
            const LatticePoint d = q[static_cast<std::size_t>((r + 3) % 4)];
            // Edge a-c: triangles (a, b, c) and (c, d, a).
            ASSERT_EQ(LatticeDelaunay::perturbed_in_circle(a, b, c, d),
                      LatticeDelaunay::perturbed_in_circle(c, d, a, b));
        }
    }
}

}  // namespace
}  // namespace sandtin
