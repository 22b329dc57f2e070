// The Jacobi schedule's bookkeeping (per-thread bitmaps, in-place gather, active set rebuilt in
// id order by three parallel phases) against a plain second implementation written from the
// definition: every active vertex computes its outflow from the old heights, every vertex that
// received or sent gathers in row order, then ActiveSet::age and activate of the changed
// vertices and their neighbours. Heights must agree bit for bit, and so must the active set,
// the changed vertices and the counts, on 1 and 2 threads, with and without bedrock, jitter
// and a relocation radius. The reference computes outflows with the plain kernel in
// reference_talus_kernel.hpp, so the optimised kernel is checked bit for bit as well, in both
// its branching and its branch-free passes (the solver picks them by how much flows), and the
// latter in SSE2 and, where the CPU runs it, AVX-512. The face rule (SlopeRule::Face) runs
// through the same bookkeeping, against its own kernel in the reference.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "physics/face_kernel.hpp"
#include "physics/talus_kernel_avx512.hpp"
#include "physics/talus_solver.hpp"
#include "physics_oracles.hpp"
#include "reference_schedule.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

/// The schedule from its definition, over whole arrays, with byte flags and no threads.
class ReferenceJacobi {
  public:
    explicit ReferenceJacobi(TalusSettings s) : settings_(s) {}

    IterationStats iterate(const AdjacencyGraph& g, const TalusArrays& a, ActiveSet& active,
                           std::vector<std::uint32_t>& changed,
                           std::vector<std::uint32_t>& splits) {
        IterationStats st;
        changed.clear();
        const std::size_t n = a.size;
        std::vector<double> q(g.slot_count(), 0.0), out(n, 0.0);
        std::vector<std::uint8_t> source(n, 0), receiver(n, 0), changed_flag(n, 0);
        std::vector<std::uint32_t> list = active.list();
        std::sort(list.begin(), list.end());  // splits are reported in id order
        for (std::uint32_t i : list) {
            source[i] = 1;
            if (g.degree(i) == 0) continue;
            out[i] = test::reference_outflow(settings_, g, a, i,
                                             test::reference_share(settings_, i, iteration_),
                                             q.data(), splits);
            st.volume_moved += out[i];
            if (out[i] > 0.0) {
                receiver[i] = 1;
                for (std::uint32_t k = g.offset(i); k < g.offset(i) + g.degree(i); ++k)
                    receiver[g.targets()[k]] = 1;
            }
        }
        st.processed = list.size();
        std::vector<double> next(a.height, a.height + n);
        for (std::uint32_t v = 0; v < n; ++v) {
            if (!receiver[v]) continue;
            double delta = source[v] ? -out[v] : 0.0;
            for (std::uint32_t k = g.offset(v); k < g.offset(v) + g.degree(v); ++k) {
                if (source[g.targets()[k]]) delta += q[g.reverses()[k]];
            }
            next[v] = std::max(a.height[v] + delta / a.area[v], a.bedrock[v]);
            if (next[v] != a.height[v]) {
                changed_flag[v] = 1;
                changed.push_back(v);
            }
        }
        std::copy(next.begin(), next.end(), a.height);
        test::age_and_wake(g, active, changed_flag, changed, settings_.quiet_iterations);
        st.changed = changed.size();
        ++iteration_;
        return st;
    }

  private:
    TalusSettings settings_;
    std::uint64_t iteration_ = 0;
};

struct Case {
    int threads;
    double randomness;
    double relocation_radius;
    bool bedrock;
    /// The branch-free rows' instruction set (TalusSettings::row_kernel): AVX-512 where the
    /// CPU runs it, unless asked otherwise.
    RowKernel row_kernel = RowKernel::Avx512;
    std::size_t vertices = 6000;
    int iterations = 300;
    SlopeRule rule = SlopeRule::Edge;
};

void compare(const Case& c) {
    SCOPED_TRACE(::testing::Message()
                 << "threads " << c.threads << ", randomness " << c.randomness << ", r_S "
                 << c.relocation_radius << ", bedrock " << c.bedrock << ", row kernel "
                 << static_cast<int>(c.row_kernel) << ", vertices " << c.vertices << ", rule "
                 << (c.rule == SlopeRule::Face ? "face" : "edge"));
    // 6000 vertices: above the threaded minimum at first, below it as the scene calms down,
    // so both the pooled and the inline paths run.
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), c.vertices, 5);
    AdjacencyGraph graph;
    graph.rebuild(tin);
    const VertexArrays& va = tin.vertices();
    const std::size_t n = va.size();
    std::mt19937_64 rng(3);
    test::ScheduleScene scene = test::schedule_scene(
        va, [](Vec2 p) { return 0.05 * std::sin(37.0 * p.x) * std::cos(29.0 * p.y); }, 0.06,
        c.bedrock, rng);
    std::vector<double>& h = scene.height;
    const std::vector<double>& b = scene.bedrock;
    const std::vector<double>& tan = scene.tan_alpha;
    std::vector<double> h_ref = h;
    // The seeds' rule keeps enough of the scene moving for the comparison to mean something.
    TalusSettings settings = seeds_rule();
    settings.schedule = Schedule::Jacobi;
    settings.threads = c.threads;
    settings.randomness = c.randomness;
    settings.seed = 9;
    settings.parameters.relocation_radius = c.relocation_radius;
    settings.row_kernel = c.row_kernel;
    settings.parameters.rule = c.rule;
    TalusSolver solver(settings);
    ReferenceJacobi reference(settings);
    const TalusArrays arrays{h.data(), va.lumped_area.data(), b.data(), tan.data(), n};
    const TalusArrays ref_arrays{h_ref.data(), va.lumped_area.data(), b.data(), tan.data(), n};
    ActiveSet active, ref_active;
    // Activated in a scrambled order: the solver must not rely on a sorted list.
    std::vector<std::uint32_t> all(n);
    for (std::uint32_t v = 0; v < n; ++v)
        all[v] = v;
    std::shuffle(all.begin(), all.end(), rng);
    active.activate(all);
    ref_active.activate(all);
    std::vector<std::uint32_t> changed_ref, splits, splits_ref;
    std::size_t moving = 0, split_total = 0;
    int branch_free = 0, branching = 0;
    for (int it = 0; it < c.iterations && !ref_active.empty(); ++it) {
        splits.clear();
        splits_ref.clear();
        (solver.jacobi_row_passes() == RowPasses::BranchFree ? branch_free : branching) += 1;
        const IterationStats s = solver.iterate(graph, arrays, active, &splits);
        const IterationStats r =
            reference.iterate(graph, ref_arrays, ref_active, changed_ref, splits_ref);
        ASSERT_EQ(s.processed, r.processed) << "iteration " << it;
        ASSERT_EQ(s.changed, r.changed) << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(solver.changed()), test::sorted_ids(changed_ref))
            << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(active.list()), test::sorted_ids(ref_active.list()))
            << "iteration " << it;
        ASSERT_EQ(test::sorted_ids(splits), test::sorted_ids(splits_ref)) << "iteration " << it;
        ASSERT_EQ(std::memcmp(h.data(), h_ref.data(), n * sizeof(double)), 0) << "iteration " << it;
        for (std::uint32_t v : active.list())
            ASSERT_TRUE(active.contains(v));
        moving += s.changed;
        split_total += splits.size();
    }
    // The scene really moved. With r_S the face rule holds back every face with an edge
    // longer than r_S at either end (about half of this coarse TIN's), so less moves.
    EXPECT_GT(moving, c.rule == SlopeRule::Face && c.relocation_radius > 0.0 ? n / 4 : n);
    if (c.relocation_radius > 0.0) {
        EXPECT_GT(split_total, 0u);
    }
    // The steep start has the kernel's branch-free passes run, the calmer end the branching
    // ones (with a relocation radius the rows always branch; where bedrock holds a third of
    // the vertices, too few edges flow at once for the branch-free passes).
    // The face rule's rows always branch.
    if (c.relocation_radius == 0.0 && !c.bedrock) {
        if (c.rule == SlopeRule::Face) {
            EXPECT_EQ(branch_free, 0);
        } else {
            EXPECT_GT(branch_free, 0);
        }
    }
    EXPECT_GT(branching, 0);
    // RowKernel::Auto measures the two kernels once enough rows run branch-free.
    if (c.row_kernel == RowKernel::Auto && avx512_rows_supported() && c.relocation_radius == 0.0 &&
        c.vertices >= TalusSolver::kRowKernelSampleRows) {
        EXPECT_TRUE(solver.row_kernel_measured());
    }
}

// One test per thread count and rule: the ThreadSanitizer pass (test.sh) runs the two-thread
// ones only, where there is something to race, and as two tests they keep both cores busy.
void compare_every_edge_rule_variant(int threads) {
    compare({threads, 0.0, 0.0, false});
    compare({threads, 0.0, 0.0, false, RowKernel::Sse2});  // on an AVX-512 CPU too
    compare({threads, 0.4, 0.0, false});
    compare({threads, 0.4, 0.0, true});
    compare({threads, 0.0, 0.012, true});
}

// The face rule (face_kernel.hpp): per-vertex tan(alpha), jitter, bedrock and r_S as well.
void compare_every_face_rule_variant(int threads) {
    Case face{threads, 0.0, 0.0, false};
    face.rule = SlopeRule::Face;
    compare(face);
    face.randomness = 0.4;
    face.bedrock = true;
    compare(face);
    face.randomness = 0.0;
    face.relocation_radius = 0.012;
    compare(face);
}

TEST(JacobiSchedule, OneThreadMatchesItsDefinitionBitForBitUnderTheEdgeRule) {
    compare_every_edge_rule_variant(1);
}

TEST(JacobiSchedule, OneThreadMatchesItsDefinitionBitForBitUnderTheFaceRule) {
    compare_every_face_rule_variant(1);
}

TEST(JacobiSchedule, TwoThreadsMatchItsDefinitionBitForBitUnderTheEdgeRule) {
    compare_every_edge_rule_variant(2);
}

TEST(JacobiSchedule, TwoThreadsMatchItsDefinitionBitForBitUnderTheFaceRule) {
    compare_every_face_rule_variant(2);
}

// RowKernel::Auto on a scene large enough to be measured: the iteration that measures computes
// its first rows in alternating chunks by both kernels, and the rest by the faster one.
void compare_while_choosing_the_row_kernel(int threads) {
    Case c{threads, 0.0, 0.0, false, RowKernel::Auto};
    c.vertices = 120000;
    c.iterations = 5;
    compare(c);
}

TEST(JacobiSchedule, OneThreadMatchesItsDefinitionWhileChoosingTheRowKernel) {
    compare_while_choosing_the_row_kernel(1);
}

TEST(JacobiSchedule, TwoThreadsMatchItsDefinitionWhileChoosingTheRowKernel) {
    compare_while_choosing_the_row_kernel(2);
}

TEST(JacobiSchedule, ActiveListComesBackInIdOrder) {
    const Tin tin = Tin::random_points(Rect::from_size(1.0, 1.0), 3000, 6);
    AdjacencyGraph graph;
    graph.rebuild(tin);
    const VertexArrays& va = tin.vertices();
    std::vector<double> h(va.size()), b(va.size(), -1e9), tan(va.size(), 0.6);
    for (std::size_t v = 0; v < h.size(); ++v)
        h[v] = 0.1 * std::sin(40.0 * va.position[v].x);
    TalusSettings settings;
    settings.schedule = Schedule::Jacobi;
    settings.threads = 2;
    TalusSolver solver(settings);
    ActiveSet active;
    for (std::uint32_t v = static_cast<std::uint32_t>(h.size()); v-- > 0;)
        active.activate(v);  // descending
    const TalusArrays arrays{h.data(), va.lumped_area.data(), b.data(), tan.data(), h.size()};
    solver.iterate(graph, arrays, active);
    ASSERT_FALSE(active.empty());
    EXPECT_TRUE(std::is_sorted(active.list().begin(), active.list().end()));
    EXPECT_TRUE(std::is_sorted(solver.changed().begin(), solver.changed().end()));
}

}  // namespace
}  // namespace sandtin
