// Randomised property tests: 4 seeds x 4000 mixed random edits (16 000 in total), with the
// mesh checked by check_valid() and by CGAL-free oracles after every batch of 250 edits.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/random_edits.hpp"
#include "support/tin_oracles.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

constexpr int kOpsPerSeed = 4000;
constexpr int kBatch = 250;

void check_batch(const Tin& tin, const std::string& where) {
    const ValidationReport r = tin.check_valid();
    ASSERT_TRUE(r.ok()) << where << "\n" << r.summary();
    const auto problems = test::mesh_problems(tin);
    ASSERT_TRUE(problems.empty()) << where << "\n" << test::join(problems);
    ASSERT_EQ(tin.triangle_count(),
              test::euler_triangle_count(tin.vertex_count(), test::border_vertex_count(tin)))
        << where;
    const VertexArrays& va = tin.vertices();
    for (std::size_t i = 0; i < va.size(); ++i) {
        if (!va.alive[i]) continue;
        ASSERT_TRUE(std::isfinite(va.height[i]) && std::isfinite(va.lumped_area[i]) &&
                    std::isfinite(va.position[i].x) && std::isfinite(va.position[i].y))
            << where << ": vertex " << i;
    }
    ASSERT_TRUE(test::close_rel(tin.volume(), test::brute_force_volume(tin), 1e-12))
        << where << ": volume " << tin.volume() << " vs triangle sum "
        << test::brute_force_volume(tin);
    // Constraint bookkeeping: every listed constraint runs along constrained edges.
    std::size_t registered = 0;
    for (const ConstraintInfo& c : tin.constraints()) {
        ++registered;
        ASSERT_GE(c.vertices.size(), 2u);
        for (std::size_t i = 0; i + 1 < c.vertices.size(); ++i) {
            ASSERT_TRUE(tin.is_constrained_edge(c.vertices[i], c.vertices[i + 1]))
                << where << ": constraint " << c.id.value;
        }
    }
    ASSERT_EQ(registered, tin.constraint_count()) << where;
}

class RandomOps : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(RandomOps, MixedEditsKeepTheTinValidAndVolumeAccounted) {
    const std::uint64_t seed = GetParam();
    const Rect domain{{-5.0, 10.0}, {5.0, 20.0}};
    Tin tin = Tin::random_points(domain, 400, seed, [](Vec2 p) {
        return 3.0 + 0.8 * std::sin(0.9 * p.x) * std::cos(1.3 * p.y) + 0.05 * p.x;
    });
    // Tracking changes but never consuming them would defer all recycling; consume now and
    // then, as the GPU mirror does.
    test::RandomEditor editor(tin, seed, {});
    std::size_t volume_failures = 0;
    std::string first_failure;
    int counts[3] = {0, 0, 0};
    std::uint64_t crossings = 0;  // vertices created where a new constraint crossed old ones
    for (int op = 1; op <= kOpsPerSeed; ++op) {
        const double before = tin.volume();
        const test::StepResult s = editor.step();
        const double after = tin.volume();
        if (s.name == "insert_constraint") crossings += s.report.vertices_created;
        const double tolerance = 1e-12 * std::abs(before);
        bool ok = true;
        if (s.conserves) {
            ok = std::abs(after - before) <= tolerance;
            ++counts[0];
        } else if (s.reported) {
            ok = std::abs(s.report.volume_change - (after - before)) <= tolerance;
            ++counts[1];
        } else {
            ++counts[2];
        }
        if (!ok && volume_failures++ == 0) {
            first_failure =
                "op " + std::to_string(op) + " (" + s.name + "): volume " + std::to_string(before) +
                " -> " + std::to_string(after) + ", reported change " +
                std::to_string(s.report.volume_change) + ", relative error " +
                std::to_string(std::abs(s.conserves ? after - before
                                                    : s.report.volume_change - (after - before)) /
                               std::abs(before));
        }
        if (op % 7 == 0) tin.take_changes();
        if (op % kBatch == 0) {
            check_batch(tin, "seed " + std::to_string(seed) + " after op " + std::to_string(op));
        }
    }
    EXPECT_EQ(volume_failures, 0u) << first_failure;
    EXPECT_GT(counts[0], kOpsPerSeed / 3);
    EXPECT_GT(counts[1], kOpsPerSeed / 10);
    EXPECT_GT(editor.generation(), 100u);
    EXPECT_GT(crossings, 10u) << "the random constraints should cross each other";
    check_batch(tin, "seed " + std::to_string(seed) + " at the end");
    // The final state survives a snapshot round trip (what saving and loading a session does).
    try {
        const Tin copy = Tin::from_snapshot(tin.snapshot());
        test::expect_snapshots_equal(tin.snapshot(), copy.snapshot(), 1e-12);
    } catch (const std::exception& e) {
        ADD_FAILURE()
            << "the final terrain (valid by check_valid) does not restore from its snapshot: "
            << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomOps, ::testing::Values(1u, 2u, 3u, 4u));

TEST(RandomOpsUntracked, MixedEditsWithoutChangeTracking) {
    // Without tracking, ids and slots are recycled at once: a different code path.
    TinOptions options;
    options.track_changes = false;
    Tin tin = Tin::random_points(
        Rect::from_size(8.0, 8.0), 300, 77,
        [](Vec2 p) { return 1.0 + 0.3 * std::sin(p.x + 2.0 * p.y); }, options);
    test::RandomEditor editor(tin, 77, {});
    for (int op = 1; op <= 1500; ++op) {
        const double before = tin.volume();
        const test::StepResult s = editor.step();
        if (s.conserves) {
            ASSERT_LE(std::abs(tin.volume() - before), 1e-12 * std::abs(before))
                << "op " << op << " " << s.name;
        }
        if (op % kBatch == 0) check_batch(tin, "untracked after op " + std::to_string(op));
    }
    EXPECT_TRUE(tin.take_changes().empty());
}

}  // namespace
}  // namespace sandtin
