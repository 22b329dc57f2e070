// insert_straying_samples: lattice detail only where the surface strays from its target.
// Oracles: the analytic target (every sample ends within the tolerance of it), the linear
// interpolation error bound h² |f''| / 8 (how few points a smooth target needs), and snapshot
// equality when the surface already holds every target.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"
#include "tools/straying_samples.hpp"
#include "tools/tool_shape.hpp"

namespace sandtin {
namespace {

const Rect kUnit = Rect::from_size(1.0, 1.0);

/// A Gaussian dip 5 cm deep and 15 cm wide: smooth, with curvature at most 2 * 0.05 / 0.15²
/// per metre.
double dip(Vec2 p) {
    return -0.05 * std::exp(-length_squared(p - Vec2{0.5, 0.5}) / (0.15 * 0.15));
}
constexpr double kDipCurvature = 2.0 * 0.05 / (0.15 * 0.15);

std::vector<Vec2> disc_lattice(double spacing) {
    std::vector<Vec2> circle;
    for (int k = 0; k < 64; ++k) {
        const double a = 2.0 * 3.14159265358979323846 * k / 64;
        circle.push_back({0.5 + 0.29 * std::cos(a), 0.5 + 0.29 * std::sin(a)});
    }
    return interior_lattice(circle, spacing);
}

double worst_miss(const Tin& tin, const std::vector<Vec2>& samples,
                  const std::vector<double>& targets) {
    double worst = 0.0;
    LocateHint hint;
    for (std::size_t k = 0; k < samples.size(); ++k)
        worst = std::max(worst, std::abs(*tin.height_at(samples[k], &hint) - targets[k]));
    return worst;
}

TEST(StrayingSamples, EverySampleEndsWithinTheToleranceWithFewPointsOnASmoothTarget) {
    const std::vector<Vec2> samples = disc_lattice(0.005);
    std::vector<double> targets;
    for (Vec2 p : samples)
        targets.push_back(dip(p));
    ASSERT_GT(samples.size(), 10000u);
    for (const double tolerance : {1e-4, 1e-3}) {
        SCOPED_TRACE(tolerance);
        // Coarse, its vertices already on the target (a stamp sets them first).
        Tin tin = Tin::random_points(kUnit, 200, 3, dip);
        EditReport edit;
        LocateHint hint;
        const std::vector<VertexId> added =
            insert_straying_samples(tin, samples, targets, tolerance, &hint, &edit);
        EXPECT_LE(worst_miss(tin, samples, targets), tolerance);
        for (VertexId v : added)
            EXPECT_EQ(tin.height(v), dip(tin.position(v)));
        // Linear interpolation along an edge of length h misses a surface of curvature k by
        // up to k h² / 8: a lattice of spacing sqrt(8 tol / k) would nearly do, area /
        // (0.866 h²) points. Greedy insertion is not optimal; four times that is still a
        // small share of the fine lattice.
        const double h2 = 8.0 * tolerance / kDipCurvature;
        const double needed = 3.14159265358979323846 * 0.29 * 0.29 / (0.866 * h2);
        EXPECT_LE(static_cast<double>(added.size()), 4.0 * needed) << needed;
        EXPECT_LT(added.size(), samples.size() / 4);
        const ValidationReport r = tin.check_valid();
        EXPECT_TRUE(r.ok()) << r.summary();
    }
}

/// The definition, written plainly: the coarse passes, then every sample in every full round
/// (one height_at each) until a round inserts nothing. insert_straying_samples only looks again
/// at samples whose triangle changed; it must end with the same terrain.
std::vector<VertexId> reference_straying(Tin& tin, const std::vector<Vec2>& samples,
                                         const std::vector<double>& targets, double tolerance,
                                         int* full_rounds) {
    std::vector<VertexId> inserted;
    LocateHint hint;
    auto pass = [&](std::size_t stride, std::size_t skip) {
        std::vector<Vec2> points;
        std::vector<double> heights;
        for (std::size_t k = 0; k < samples.size(); k += stride) {
            if (skip != 0 && k % skip == 0) continue;
            const std::optional<double> h = tin.height_at(samples[k], &hint);
            if (!h) continue;
            const double slack = 8.0 * std::numeric_limits<double>::epsilon() *
                                 std::max(std::abs(*h), std::abs(targets[k]));
            if (!(std::abs(*h - targets[k]) <= tolerance + slack)) {
                points.push_back(samples[k]);
                heights.push_back(targets[k]);
            }
        }
        const std::vector<VertexId> ids = tin.insert_points(points, heights, &hint);
        inserted.insert(inserted.end(), ids.begin(), ids.end());
        return points.size();
    };
    pass(64, 0);
    pass(16, 64);
    pass(4, 16);
    *full_rounds = 1;
    while (pass(1, 0) != 0 && *full_rounds < 8)
        ++*full_rounds;
    return inserted;
}

TEST(StrayingSamples, LookingAgainOnlyWhereTrianglesChangedGivesTheSameTerrain) {
    // A rough target (a sharp crease and ripples) on a random TIN: insertions re-triangulate
    // well beyond their own sample, so several full rounds insert more.
    auto rough = [](Vec2 p) {
        return 0.02 * std::abs(p.x - 0.47) + 0.004 * std::sin(90.0 * p.y) + dip(p);
    };
    const std::vector<Vec2> samples = disc_lattice(0.006);
    std::vector<double> targets;
    for (Vec2 p : samples)
        targets.push_back(rough(p));
    // Or with vertices exactly on every 7th sample, at the wrong height: there a stray sample
    // changes that vertex's height instead of the triangles, and its neighbours' samples move.
    std::vector<Vec2> on_samples;
    std::vector<double> off_target;
    for (std::size_t k = 0; k < samples.size(); k += 7) {
        on_samples.push_back(samples[k]);
        off_target.push_back(targets[k] + 0.003);
    }
    auto terrain = [&](bool vertices_on_samples) {
        return vertices_on_samples ? Tin::from_points(kUnit, on_samples, off_target)
                                   : Tin::random_points(kUnit, 3000, 9, dip);
    };
    int most_rounds = 0;
    for (const auto& [tolerance, vertices_on_samples] :
         {std::pair{2e-4, false}, std::pair{1e-3, false}, std::pair{2e-4, true}}) {
        SCOPED_TRACE(std::to_string(tolerance) + (vertices_on_samples ? ", on samples" : ""));
        Tin reference = terrain(vertices_on_samples);
        Tin tin = terrain(vertices_on_samples);
        int rounds = 0;
        const std::vector<VertexId> want =
            reference_straying(reference, samples, targets, tolerance, &rounds);
        most_rounds = std::max(most_rounds, rounds);
        LocateHint hint;
        const std::vector<VertexId> got =
            insert_straying_samples(tin, samples, targets, tolerance, &hint, nullptr);
        EXPECT_EQ(got, want);
        test::expect_snapshots_equal(reference.snapshot(), tin.snapshot());
    }
    EXPECT_GE(most_rounds, 3);  // the case this is about: later rounds that still insert
}

TEST(StrayingSamples, AVertexHeightSetBySampleSendsTheSamplesAroundItBackForAnotherLook) {
    // Triangle A B V with A, B 1 cm above the target (0) and V 2 cm below it. Sample s1 sits
    // where V weighs a third: the errors cancel and s1 does not stray at first. Sample s0 lies
    // exactly on V and strays: inserting it sets V's height (the triangles stay as they are),
    // and only then does s1 stray (by 2/3 cm). Its triangle's corners did not change their
    // stars, only V its height; a later round must look at s1 again.
    const std::vector<Vec2> vertices = {{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}};
    const std::vector<double> heights = {0.01, 0.01, -0.02};
    const std::vector<Vec2> samples = {{0.5, 0.4}, {0.5, 0.8}};  // s1 first: the coarse pass
    const std::vector<double> targets = {0.0, 0.0};              // sees it alone
    Tin tin = Tin::from_points(kUnit, vertices, heights);
    ASSERT_NEAR(*tin.height_at(samples[0]), 0.0, 1e-15);
    LocateHint hint;
    const std::vector<VertexId> added =
        insert_straying_samples(tin, samples, targets, 1e-3, &hint, nullptr);
    EXPECT_EQ(added.size(), 2u);
    EXPECT_LE(worst_miss(tin, samples, targets), 1e-3);
}

TEST(StrayingSamples, ASurfaceThatHoldsEveryTargetIsLeftAlone) {
    // The TIN is built on the samples themselves: nothing strays, nothing changes.
    const std::vector<Vec2> samples = disc_lattice(0.02);
    std::vector<double> targets;
    for (Vec2 p : samples)
        targets.push_back(dip(p));
    Tin tin = Tin::from_points(kUnit, samples, targets);
    const TinSnapshot before = tin.snapshot();
    LocateHint hint;
    EXPECT_TRUE(insert_straying_samples(tin, samples, targets, 0.0, &hint, nullptr).empty());
    test::expect_snapshots_equal(before, tin.snapshot());
}

TEST(StrayingSamples, ZeroToleranceInsertsEverySampleOffTheSurface) {
    // On a flat TIN, every sample whose target is not 0 strays.
    const std::vector<Vec2> samples = disc_lattice(0.03);
    std::vector<double> targets;
    std::size_t off = 0;
    for (Vec2 p : samples) {
        targets.push_back(dip(p));
        off += dip(p) != 0.0 ? 1 : 0;
    }
    Tin tin = Tin::flat_rectangle(kUnit);
    LocateHint hint;
    const auto added = insert_straying_samples(tin, samples, targets, 0.0, &hint, nullptr);
    EXPECT_GE(added.size(), off / 2);  // coarse samples already pull their neighbours along
    EXPECT_LE(worst_miss(tin, samples, targets), 1e-15);  // interpolation rounding only
}

TEST(StrayingSamples, BadInputIsAClearErrorAndOddSamplesAreSkipped) {
    Tin tin = Tin::flat_rectangle(kUnit);
    const TinSnapshot before = tin.snapshot();
    LocateHint hint;
    const std::vector<Vec2> two = {{0.2, 0.2}, {0.4, 0.4}};
    const std::vector<double> one = {0.1};
    try {
        insert_straying_samples(tin, two, one, 0.0, &hint, nullptr);
        ADD_FAILURE() << "size mismatch accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("one target height per sample"), std::string::npos);
    }
    const std::vector<double> both = {0.1, 0.1};
    for (const double bad : {-1e-3, std::numeric_limits<double>::quiet_NaN()}) {
        try {
            insert_straying_samples(tin, two, both, bad, &hint, nullptr);
            ADD_FAILURE() << "tolerance " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("tolerance"), std::string::npos);
        }
    }
    test::expect_snapshots_equal(before, tin.snapshot());
    // Outside the domain, a NaN target: skipped. Two samples at one place with different
    // targets: the passes stop (the last one written wins), no endless tug of war.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Vec2> odd = {{1.5, 0.5}, {0.3, 0.3}, {0.6, 0.6}, {0.6, 0.6}};
    const std::vector<double> odd_targets = {0.2, nan, 0.1, 0.3};
    const auto added = insert_straying_samples(tin, odd, odd_targets, 0.0, &hint, nullptr);
    EXPECT_FALSE(added.empty());
    EXPECT_FALSE(tin.locate({0.3, 0.3}).kind == Location::Kind::OnVertex);
    const ValidationReport r = tin.check_valid();
    EXPECT_TRUE(r.ok()) << r.summary();
}

}  // namespace
}  // namespace sandtin
