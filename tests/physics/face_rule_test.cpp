// The face rule (SlopeRule::Face, physics/face_kernel.hpp): sand comes to rest with every
// triangle at most as steep as repose, not only every edge (issue 39). Oracles: the per-face
// measure (physics/face_slopes), the analytic cone, and the volume ledger.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "physics/adjacency_graph.hpp"
#include "physics/cone.hpp"
#include "physics/face_kernel.hpp"
#include "physics/face_slopes.hpp"
#include "physics/sand_physics.hpp"
#include "physics_oracles.hpp"

namespace sandtin {
namespace {

constexpr double kFacePileVolume = 0.01;  // m³: a cone of radius ~0.25 m at 32°
const Vec2 kFacePileCentre{0.5, 0.5};

double repose_tan() {
    return MaterialTable::presets().at(0).talus_slope(0.0);
}

TEST(FaceCorner, FootAndAltitudeOfKnownTriangles) {
    // i at (0, 1), j at (-1, 0), l at (2, 0): the altitude from i meets jl at (0, 0), a third of
    // the way from j, 1 m below i.
    const FaceCorner inside = face_corner(std::sqrt(2.0), std::sqrt(5.0), 3.0);
    EXPECT_NEAR(inside.foot, 1.0 / 3.0, 1e-15);
    EXPECT_NEAR(inside.altitude, 1.0, 1e-15);
    // i at (3, 2) over j (0, 0) and l (1, 0): the foot (3, 0) lies past l, at 3 |jl| from j.
    const FaceCorner outside = face_corner(std::sqrt(13.0), std::sqrt(8.0), 1.0);
    EXPECT_NEAR(outside.foot, 3.0, 1e-14);
    EXPECT_NEAR(outside.altitude, 2.0, 1e-14);
    // i on the line jl (at its middle), and a pair of neighbours with no face between them:
    // nothing to judge, and the face rule skips both.
    EXPECT_EQ(face_corner(1.0, 1.0, 2.0).altitude, 0.0);
    EXPECT_EQ(face_corner(1.0, 1.0, 0.0).altitude, 0.0);
    TalusParameters p;
    EXPECT_EQ(detail::face_shed(1.0, 1.0, 2.0, 10.0, 0.0, 0.0, repose_tan(), p, 0.0).excess, 0.0);
}

TEST(FaceCorner, AGraphWithoutShapesSendsWhatOneWithThemSends) {
    // The GPU mirror's graph keeps no shapes (FaceShapes::Skip) and the kernel then works them
    // out per face, as it did before graphs kept them: both must send the same, bit for bit.
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 600, 41);
    std::vector<VertexId> ids;
    std::vector<double> heights;
    for (std::uint32_t v = 0; v < tin.vertices().size(); ++v) {
        if (!tin.vertices().alive[v]) continue;
        const Vec2 p = tin.vertices().position[v];
        ids.push_back(VertexId{v});
        heights.push_back(0.3 * std::sin(9.0 * p.x) * std::cos(7.0 * p.y) + 0.4 * p.x);
    }
    tin.set_heights(ids, heights);
    AdjacencyGraph kept(RowSlack::None, FaceShapes::Keep);
    AdjacencyGraph skipped(RowSlack::None, FaceShapes::Skip);
    kept.rebuild(tin);
    skipped.rebuild(tin);
    ASSERT_NE(kept.face_rows().corner, nullptr);
    ASSERT_EQ(skipped.face_rows().corner, nullptr);
    const VertexArrays& va = tin.vertices();
    TalusParameters p;
    std::vector<double> q_kept(kept.slot_count()), q_skipped(skipped.slot_count());
    std::size_t sending = 0;
    auto no_split = [](std::uint32_t) {};
    for (VertexId v : ids) {
        const std::uint32_t i = v.value;
        const double a = face_outflow(
            i, kept.offset(i), kept.degree(i), kept.targets().data(), kept.lengths().data(),
            kept.face_rows(), kept.longest_edges().data(), va.height.data(), va.lumped_area.data(),
            va.bedrock.data(), repose_tan(), p, 1.0, q_kept.data(), no_split);
        const double b =
            face_outflow(i, skipped.offset(i), skipped.degree(i), skipped.targets().data(),
                         skipped.lengths().data(), skipped.face_rows(),
                         skipped.longest_edges().data(), va.height.data(), va.lumped_area.data(),
                         va.bedrock.data(), repose_tan(), p, 1.0, q_skipped.data(), no_split);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "vertex " << i;
        for (std::uint32_t k = 0; k < kept.degree(i); ++k)
            ASSERT_EQ(std::memcmp(&q_kept[kept.offset(i) + k], &q_skipped[skipped.offset(i) + k],
                                  sizeof(double)),
                      0);
        sending += a > 0.0 ? 1 : 0;
    }
    EXPECT_GT(sending, ids.size() / 10);  // the surface is steep enough for the test to bite
    EXPECT_TRUE(kept.matches(tin));
    EXPECT_TRUE(skipped.matches(tin));
}

TEST(FaceShed, ALevelledFaceHasTheGradientOfRepose) {
    // i at (0, 1), j at (-1, 0), l at (2, 0): a = sqrt 2, b = sqrt 5, c = 3.
    const double a = std::sqrt(2.0), b = std::sqrt(5.0), c = 3.0;
    TalusParameters p;
    p.settle_margin = 0.0;
    const double t = repose_tan();
    const double hj = 0.1, hl = 0.4;
    const detail::FaceShed f = detail::face_shed(a, b, c, 5.0, hj, hl, t, p, 0.0);
    ASSERT_GT(f.excess, 0.0);
    // Lowered by the excess, i makes the face exactly as steep as repose.
    const double hi = 5.0 - f.excess;
    EXPECT_NEAR(face_gradient({0, 1, hi}, {-1, 0, hj}, {2, 0, hl}), t, 1e-12);
    // The shares follow the steepest-descent line and add to 1.
    EXPECT_NEAR(f.to_j + f.to_l, 1.0, 1e-15);
    EXPECT_GT(f.to_j, 0.0);
    EXPECT_GT(f.to_l, 0.0);
    // A face already gentler than repose sheds nothing.
    EXPECT_EQ(detail::face_shed(a, b, c, hi - 1e-3, hj, hl, t, p, 0.0).excess, 0.0);
}

TEST(FaceShed, SandNeverClimbs) {
    // i barely above the line, j far above i: everything goes to l.
    TalusParameters p;
    const double a = std::sqrt(2.0), b = std::sqrt(5.0), c = 3.0;
    const detail::FaceShed f = detail::face_shed(a, b, c, 1.0, 1.2, -1.5, repose_tan(), p, 0.0);
    ASSERT_GT(f.excess, 0.0);
    EXPECT_EQ(f.to_j, 0.0);
    EXPECT_EQ(f.to_l, 1.0);
}

struct Rested {
    FaceSlopeReport faces;
    test::PileShape shape;
    Cone cone;
    double volume_error = 0.0;
    bool at_rest = false;
    int iterations = 0;
};

Rested pour_face_rule(Tin& tin, double relocation_radius, int portions, int between,
                      double settle_margin, Schedule schedule = Schedule::Sequential,
                      int threads = 1) {
    TalusSettings settings;
    settings.schedule = schedule;
    settings.threads = threads;
    settings.parameters.rule = SlopeRule::Face;
    settings.parameters.settle_margin = settle_margin;
    settings.parameters.relocation_radius = relocation_radius;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    const double before = tin.volume();
    const VertexId apex =
        test::pour_at_point(tin, physics, kFacePileCentre, kFacePileVolume / portions);
    PhysicsStepReport r;
    for (int k = 1; k < portions; ++k) {
        r.accumulate(physics.step(between));
        tin.set_height(apex, tin.height(apex) + kFacePileVolume / portions /
                                                    tin.vertices().lumped_area[apex.value]);
    }
    r.accumulate(physics.run_to_rest(400000));
    Rested out;
    out.at_rest = r.at_rest;
    out.iterations = r.iterations;
    // Flowing sand levels towards (1 - m) tan(alpha) (the settle margin): the pile rests between
    // that and tan(alpha), and the cone at (1 - m) tan(alpha) is the reference.
    out.cone = Cone::from_volume(kFacePileVolume, (1.0 - settle_margin) * repose_tan());
    out.faces = measure_face_slopes(tin, MaterialTable::presets());
    out.shape =
        test::measure_pile(tin, kFacePileCentre, 2.0 * out.cone.radius, 1e-3 * out.cone.height);
    out.volume_error = std::abs(tin.volume() - before - kFacePileVolume) / kFacePileVolume;
    std::printf(
        "  %s: vertices %zu, iterations %d, steep faces %zu of %zu (%.3g of the slopes), "
        "steepest %.5f, apex %.5f (cone %.5f), toe %.5f (cone %.5f)\n",
        schedule == Schedule::Jacobi ? "Jacobi" : "sequential", tin.vertex_count(), r.iterations,
        out.faces.steep_faces, out.faces.faces, out.faces.steep_share_of_slopes(),
        out.faces.max_ratio, out.shape.apex, out.cone.height, out.shape.toe_radius,
        out.cone.radius);
    return out;
}

void expect_rested_cone(const Rested& r) {
    EXPECT_TRUE(r.at_rest);
    EXPECT_EQ(r.faces.steep_faces, 0u) << "steepest " << r.faces.max_ratio << " at "
                                       << r.faces.steepest_at.x << ", " << r.faces.steepest_at.y;
    EXPECT_LT(r.volume_error, 1e-12);
    EXPECT_NEAR(r.shape.apex, r.cone.height, 0.03 * r.cone.height);
    EXPECT_NEAR(r.shape.toe_radius, r.cone.radius, 0.02 * r.cone.radius);
}

TEST(FaceRule, AConeOnADenseRandomTinRestsWithNoFaceSteeperThanRepose) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 20000, 7);
    expect_rested_cone(pour_face_rule(tin, 0.0, 1, 0, TalusParameters{}.settle_margin));
}

TEST(FaceRule, AConeFromTwoTrianglesRestsWithNoFaceSteeperThanRepose) {
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0));
    expect_rested_cone(pour_face_rule(tin, 0.02, 100, 50, TalusParameters{}.settle_margin));
    EXPECT_TRUE(tin.check_valid().ok());
}

/// Rough sand 0 to 4 cm over a bedrock 1 cm under the lowest point, eroded `iterations` times
/// under the face rule: the volume (sum of A_i h_i) must stay put and no vertex go below the
/// bedrock.
void expect_face_rule_conserves(Schedule schedule, int threads, int iterations) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 4000, 12, [](Vec2 p) {
        return 0.02 + 0.02 * std::sin(40.0 * p.x) * std::cos(33.0 * p.y);
    });
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) tin.set_bedrock(VertexId{v}, std::min(va.height[v], 0.01));
    }
    TalusSettings settings;
    settings.schedule = schedule;
    settings.threads = threads;
    settings.parameters.rule = SlopeRule::Face;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    physics.activate_all();
    const double before = tin.volume();
    const PhysicsStepReport r = physics.step(iterations);
    EXPECT_GT(r.volume_moved, 1e-4);
    EXPECT_LE(std::abs(tin.volume() - before), 1e-12 * before);
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) {
            EXPECT_GE(va.height[v], va.bedrock[v]) << v;
        }
    }
}

TEST(FaceRule, MovesVolumeExactlyAndNeverBelowTheBedrock) {
    expect_face_rule_conserves(Schedule::Sequential, 1, 3000);
}

TEST(FaceRuleJacobi, MovesVolumeExactlyAndNeverBelowTheBedrock) {
    // 10^5 iterations: once the sand rests they cost nothing (the active set is empty).
    expect_face_rule_conserves(Schedule::Jacobi, 2, 100000);
}

TEST(FaceRuleJacobi, AConeOnADenseRandomTinRestsAsTheSequentialOneDoes) {
    const double margin = TalusParameters{}.settle_margin;
    Tin sequential_tin = Tin::random_points(Rect::from_size(1.0, 1.0), 20000, 7);
    const Rested sequential = pour_face_rule(sequential_tin, 0.0, 1, 0, margin);
    Tin jacobi_tin = Tin::random_points(Rect::from_size(1.0, 1.0), 20000, 7);
    const Rested jacobi = pour_face_rule(jacobi_tin, 0.0, 1, 0, margin, Schedule::Jacobi, 2);
    expect_rested_cone(sequential);
    expect_rested_cone(jacobi);
    // The same sand, and two rests of one rule: the same pile within the rule's spread.
    EXPECT_NEAR(jacobi_tin.volume(), sequential_tin.volume(), 1e-12 * sequential_tin.volume());
    EXPECT_NEAR(jacobi.shape.apex, sequential.shape.apex, 0.02 * sequential.shape.apex);
    EXPECT_NEAR(jacobi.shape.toe_radius, sequential.shape.toe_radius,
                0.02 * sequential.shape.toe_radius);
}

TEST(FaceRuleJacobi, AConeFromTwoTrianglesRestsWithNoFaceSteeperThanRepose) {
    // r_S splits the long edges the pour meets (needs_split), as the sequential test does.
    Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0));
    expect_rested_cone(
        pour_face_rule(tin, 0.02, 100, 50, TalusParameters{}.settle_margin, Schedule::Jacobi, 2));
    EXPECT_TRUE(tin.check_valid().ok());
}

TEST(FaceRuleJacobi, OneAndTwoThreadsGiveTheSameTerrainBitForBit) {
    // With r_S, so the splits the threads report are part of what must agree, and with jitter.
    std::vector<double> heights[2];
    for (int threads = 1; threads <= 2; ++threads) {
        Tin tin = Tin::flat_rectangle(Rect::from_size(1.0, 1.0));
        TalusSettings settings;
        settings.schedule = Schedule::Jacobi;
        settings.threads = threads;
        settings.randomness = 0.3;
        settings.seed = 17;
        settings.parameters.rule = SlopeRule::Face;
        settings.parameters.relocation_radius = 0.02;
        SandPhysics physics(tin, MaterialTable::presets(), settings);
        test::pour_at_point(tin, physics, kFacePileCentre, kFacePileVolume);
        EXPECT_TRUE(physics.run_to_rest(400000).at_rest);
        const VertexArrays& va = tin.vertices();
        heights[threads - 1].assign(va.height.begin(), va.height.end());
        EXPECT_GT(tin.vertex_count(), 1000u);  // r_S refined the pile
    }
    ASSERT_EQ(heights[0].size(), heights[1].size());
    EXPECT_EQ(std::memcmp(heights[0].data(), heights[1].data(), heights[0].size() * sizeof(double)),
              0);
}

/// Dune-like sand: crests running across the domain, each with a gentle stoss side and a
/// vertical lee (a sawtooth in a wavy coordinate), 5 cm high, over a bedrock at 5 mm.
double face_rule_dune(Vec2 p) {
    const double u = 6.0 * p.x + 0.4 * std::sin(7.0 * p.y) + 0.15 * std::sin(19.0 * p.y);
    return 0.005 + 0.05 * (u - std::floor(u));
}

/// The dunes (face_rule_dune) on a random TIN, eroded to rest under the face rule in
/// `schedule`: at rest, no face steeper than repose, the volume kept. Returns the iterations.
int face_rule_dunes_to_rest(Schedule schedule) {
    Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 12000, 21, face_rule_dune);
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) tin.set_bedrock(VertexId{v}, std::min(va.height[v], 0.005));
    }
    const FaceSlopeReport before_faces = measure_face_slopes(tin, MaterialTable::presets());
    EXPECT_GT(before_faces.steep_faces, 100u);  // the lee sides are far steeper than repose
    TalusSettings settings;
    settings.schedule = schedule;
    settings.threads = 2;
    settings.parameters.rule = SlopeRule::Face;
    SandPhysics physics(tin, MaterialTable::presets(), settings);
    physics.activate_all();
    const double before = tin.volume();
    const PhysicsStepReport r = physics.run_to_rest(200000);
    const FaceSlopeReport faces = measure_face_slopes(tin, MaterialTable::presets());
    std::printf(
        "  dunes, %s: iterations %d, steep faces %zu of %zu before, %zu after "
        "(steepest %.5f)\n",
        schedule == Schedule::Jacobi ? "Jacobi" : "sequential", r.iterations,
        before_faces.steep_faces, before_faces.faces, faces.steep_faces, faces.max_ratio);
    EXPECT_TRUE(r.at_rest);
    EXPECT_EQ(faces.steep_faces, 0u) << "steepest " << faces.max_ratio;
    EXPECT_LE(std::abs(tin.volume() - before), 1e-12 * before);
    // A terrain at rest costs nothing: no vertex is processed.
    EXPECT_EQ(physics.step(100).vertex_updates, 0u);
    return r.iterations;
}

TEST(FaceRuleJacobi, DunesOnARandomTinRestWithNoFaceSteeperThanRepose) {
    const int jacobi = face_rule_dunes_to_rest(Schedule::Jacobi);
    const int sequential = face_rule_dunes_to_rest(Schedule::Sequential);
    // Jacobi sees its neighbours' old heights, so it may take more iterations, but it must not
    // oscillate without end (measured: 551 iterations against the sequential 299).
    EXPECT_LT(jacobi, 5 * sequential);
}

}  // namespace
}  // namespace sandtin
