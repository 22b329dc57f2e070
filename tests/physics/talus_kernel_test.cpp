// The production talus kernel (engine/physics/talus_kernel.hpp, specialised at compile time
// for the relocation radius, in both its branching and its branch-free passes) against the
// plain one written from the definition (reference_talus_kernel.hpp): the same volumes bit for
// bit, the same total and the same split requests in the same order, on random rows of 1 to
// 40 slots (odd and even, for the two-lane passes), with and without a relocation radius,
// bedrock, levelling shares (jittered, some past 1) and a settle margin.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/talus_kernel.hpp"
#include "physics/talus_solver.hpp"
#include "reference_talus_kernel.hpp"
#include "tin/tin.hpp"

namespace sandtin {
namespace {

TEST(TalusKernel, MatchesThePlainKernelBitForBit) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    constexpr std::uint32_t kVertices = 64;
    std::size_t flowing_rows = 0, split_rows = 0, long_rows = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const auto degree = static_cast<std::uint32_t>(1 + rng() % (trial % 10 == 0 ? 40 : 9));
        std::vector<std::uint32_t> target(degree);
        std::vector<double> length(degree);
        std::vector<double> height(kVertices), area(kVertices), bedrock(kVertices);
        std::vector<double> longest(kVertices);
        for (std::uint32_t v = 0; v < kVertices; ++v) {
            height[v] = u(rng) < 0.1 ? 0.3 : 0.3 * u(rng) - 0.1;  // some exact ties
            // Some small vertices, and some degenerate ones (vertical slivers).
            const double kind = u(rng);
            area[v] = kind < 0.1 ? 1e-6 : kind < 0.15 ? 1e-13 : 1e-4 * (0.1 + u(rng));
            bedrock[v] = u(rng) < 0.3 ? height[v] - 0.01 * u(rng) : -1.0;
            longest[v] = 0.02 * u(rng);
        }
        for (std::uint32_t k = 0; k < degree; ++k) {
            target[k] = 1 + static_cast<std::uint32_t>(rng() % (kVertices - 1));
            length[k] = 0.001 + 0.015 * u(rng);
        }
        TalusParameters p;
        p.relocation_radius = trial % 3 == 0 ? 0.012 : 0.0;
        p.settle_margin = trial % 4 == 0 ? 0.05 : 0.0;
        p.rest_tolerance = trial % 5 == 0 ? 0.0 : 1e-4;
        const double tan_alpha = 0.3 + 0.5 * u(rng);
        // The levelling share: the Jacobi schedule's (damping, jittered), or the sequential
        // schedule's whole levelling, jittered past 1 (taken as 1) in some trials.
        const double share =
            trial % 3 == 0 ? 1.0 : (trial % 3 == 1 ? 0.5 : 1.0) * (0.7 + 0.6 * u(rng));
        std::vector<double> q_ref(degree, -2.0);
        std::vector<std::uint32_t> splits_ref;
        const double sent_ref = test::reference_talus_outflow(
            0, 0, degree, target.data(), length.data(), longest.data(), height.data(), area.data(),
            bedrock.data(), tan_alpha, p, share, q_ref.data(),
            [&](std::uint32_t v) { splits_ref.push_back(v); });
        // Both of the kernel's passes against the reference.
        auto expect_reference = [&]<RowPasses kPasses>() {
            std::vector<double> q(degree, -1.0);
            std::vector<std::uint32_t> splits;
            const double sent = talus_outflow<kPasses>(
                0, 0, degree, target.data(), length.data(), longest.data(), height.data(),
                area.data(), bedrock.data(), tan_alpha, p, share, q.data(),
                [&](std::uint32_t v) { splits.push_back(v); });
            EXPECT_EQ(std::memcmp(&sent, &sent_ref, sizeof(double)), 0);
            EXPECT_EQ(std::memcmp(q.data(), q_ref.data(), degree * sizeof(double)), 0);
            EXPECT_EQ(splits, splits_ref);
        };
        SCOPED_TRACE(::testing::Message() << "trial " << trial);
        expect_reference.template operator()<RowPasses::Branching>();
        expect_reference.template operator()<RowPasses::BranchFree>();
        if (HasFailure()) return;  // one failing trial says it all
        flowing_rows += sent_ref > 0.0 ? 1 : 0;
        split_rows += splits_ref.empty() ? 0 : 1;
        long_rows += degree > 32 && sent_ref > 0.0 ? 1 : 0;
    }
    // The trials really exercise flow, splits and the long-row path.
    EXPECT_GT(flowing_rows, 5000u);
    EXPECT_GT(split_rows, 1000u);
    EXPECT_GT(long_rows, 100u);
}

// The levelling share (physics/talus_kernel.hpp): with share 1 (the sequential schedule) a
// lone steep edge is levelled in one step, to (1 - m) r tan(alpha) exactly; with share 1/2
// (Jacobi, damping 1/2) half its excess goes; where several edges flow, the cap holds the
// sender's drop to damping times its largest excess whatever the share; a jittered share past 1
// moves no more than share 1. Worked out by hand from the definitions, for both passes.
template <RowPasses kPasses>
void expect_levelling_share_and_cap() {
    const TalusParameters p;  // damping 1/2, settle margin 0.03
    const double tan_alpha = 0.6, r = 0.1;
    const std::vector<double> length = {r, r, r};
    const std::vector<double> longest(4, r);
    const std::vector<double> bedrock(4, -10.0);
    auto step = [&](std::uint32_t degree, const std::vector<double>& area, double share,
                    std::vector<double> height) {
        const std::vector<std::uint32_t> target = {1, 2, 3};
        std::vector<double> q(degree, -1.0);
        const double sent = talus_outflow<kPasses>(
            0, 0, degree, target.data(), length.data(), longest.data(), height.data(), area.data(),
            bedrock.data(), tan_alpha, p, share, q.data(), [](std::uint32_t) {});
        height[0] -= sent / area[0];
        for (std::uint32_t k = 0; k < degree; ++k)
            height[target[k]] += q[k] / area[target[k]];
        return height;
    };
    const double level = (1.0 - p.settle_margin) * r * tan_alpha;  // what a flowing edge levels to
    // A lone edge 0.2 m steeper than repose between equal areas.
    const std::vector<double> steep = {0.2 + r * tan_alpha, 0.0, 5.0, 5.0};
    const std::vector<double> equal(4, 0.01);
    const std::vector<double> whole = step(1, equal, 1.0, steep);
    EXPECT_NEAR(whole[0] - whole[1], level, 1e-15);
    const double excess = steep[0] - steep[1] - level;  // at the settle margin
    std::vector<double> h = step(1, equal, 0.5, steep);
    EXPECT_NEAR(h[0] - h[1], level + 0.5 * excess, 1e-15);
    // Past 1: the same as 1 (never more than levels the edge).
    h = step(1, equal, 1.3, steep);
    EXPECT_EQ(h, whole);
    // Three equally steep edges: levelling each alone would drop the sender by 3/2 of the
    // excess; the cap holds it to damping times the excess, shared equally, at either share.
    const std::vector<double> three = {0.2 + r * tan_alpha, 0.0, 0.0, 0.0};
    for (const double share : {1.0, 0.5}) {
        h = step(3, equal, share, three);
        EXPECT_NEAR(three[0] - h[0], p.damping * excess, 1e-15) << "share " << share;
        for (int k = 1; k <= 3; ++k)
            EXPECT_NEAR(h[k], p.damping * excess / 3.0, 1e-15) << "share " << share;
    }
    // A receiver 100 times smaller: share 1 levels the edge (the receiver rises by nearly the
    // whole excess, the sender barely drops), within the cap.
    h = step(1, {1.0, 0.01, 0.01, 0.01}, 1.0, steep);
    EXPECT_NEAR(h[0] - h[1], level, 1e-14);
    EXPECT_LT(steep[0] - h[0], 0.01 * excess);
}

TEST(TalusKernel, LevellingShareAndTheCapOnTheDrop) {
    {
        SCOPED_TRACE("branching passes");
        expect_levelling_share_and_cap<RowPasses::Branching>();
    }
    {
        SCOPED_TRACE("branch-free passes");
        expect_levelling_share_and_cap<RowPasses::BranchFree>();
    }
}

/// Settings out of range are refused by the solver with a message naming the setting.
// An edge into a vertex with under a millionth of the sender's lumped area carries nothing (a
// vertical sliver passes on at once whatever it gets, so the slope above it would creep
// forever); one with a hundred-thousandth of it flows, and the sliver itself sends as usual.
template <RowPasses kPasses>
void expect_degenerate_receivers_take_nothing() {
    // Vertex 0 stands 1 m above three neighbours 0.1 m away, all far steeper than repose.
    const std::vector<std::uint32_t> target = {1, 2, 3};
    const std::vector<double> length = {0.1, 0.1, 0.1};
    const std::vector<double> longest = {0.1, 0.1, 0.1, 0.1};
    const std::vector<double> height = {1.0, 0.0, 0.0, 0.0};
    const std::vector<double> bedrock(4, -10.0);
    const TalusParameters p;
    const double tan_alpha = 0.6;
    auto outflow = [&](const std::vector<double>& area, std::vector<double>& q) {
        q.assign(3, -1.0);
        return talus_outflow<kPasses>(0, 0, 3, target.data(), length.data(), longest.data(),
                                      height.data(), area.data(), bedrock.data(), tan_alpha, p, 1.0,
                                      q.data(), [](std::uint32_t) {});
    };
    std::vector<double> q;
    // Receiver 1 at 1e-7 of the sender's area: nothing; receiver 2 at 1e-5: flows.
    const double sent = outflow({0.1, 1e-8, 1e-6, 0.1}, q);
    EXPECT_EQ(q[0], 0.0);
    EXPECT_GT(q[1], 0.0);
    EXPECT_GT(q[2], 0.0);
    EXPECT_EQ(sent, q[1] + q[2]);
    // The sliver as the sender: every receiver is far larger, so it sends to all three.
    std::vector<double> sliver_area = {1e-8, 0.1, 0.1, 0.1};
    EXPECT_GT(outflow(sliver_area, q), 0.0);
    EXPECT_GT(q[0], 0.0);
    EXPECT_GT(q[1], 0.0);
    EXPECT_GT(q[2], 0.0);
    // Every steep edge into a degenerate receiver: nothing leaves, and every slot says so.
    EXPECT_EQ(outflow({0.1, 1e-8, 1e-8, 1e-9}, q), 0.0);
    EXPECT_EQ(q, std::vector<double>(3, 0.0));
}

TEST(TalusKernel, DegenerateReceiversTakeNothing) {
    {
        SCOPED_TRACE("branching passes");
        expect_degenerate_receivers_take_nothing<RowPasses::Branching>();
    }
    {
        SCOPED_TRACE("branch-free passes");
        expect_degenerate_receivers_take_nothing<RowPasses::BranchFree>();
    }
}

TEST(TalusSettings, OutOfRangeIsAClearError) {
    const Tin tin = Tin::regular_grid(Rect::from_size(1.0, 1.0), 4, 4);
    AdjacencyGraph graph;
    graph.rebuild(tin);
    const VertexArrays& va = tin.vertices();
    std::vector<double> h(va.size(), 0.0), b(va.size(), -1.0), tan(va.size(), 0.6);
    h[0] = 1.0;
    const TalusArrays arrays{h.data(), va.lumped_area.data(), b.data(), tan.data(), h.size()};
    auto message = [&](auto change) -> std::string {
        TalusSettings settings;
        change(settings);
        TalusSolver solver(settings);
        ActiveSet active;
        for (std::uint32_t v = 0; v < h.size(); ++v)
            active.activate(v);
        try {
            solver.iterate(graph, arrays, active);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "accepted";
    };
    EXPECT_EQ(message([](TalusSettings&) {}), "accepted");
    EXPECT_NE(message([](TalusSettings& s) { s.parameters.damping = 0.0; }).find("damping"),
              std::string::npos);
    EXPECT_NE(message([](TalusSettings& s) { s.parameters.damping = 1.5; }).find("damping"),
              std::string::npos);
    EXPECT_NE(
        message([](TalusSettings& s) { s.parameters.settle_margin = 1.0; }).find("settle_margin"),
        std::string::npos);
    EXPECT_NE(
        message([](TalusSettings& s) { s.parameters.settle_margin = -0.1; }).find("settle_margin"),
        std::string::npos);
    EXPECT_NE(message([](TalusSettings& s) {
                  s.parameters.rest_tolerance = std::nan("");
              }).find("rest_tolerance"),
              std::string::npos);
    EXPECT_NE(message([](TalusSettings& s) {
                  s.parameters.relocation_radius = -1.0;
              }).find("relocation_radius"),
              std::string::npos);
    EXPECT_NE(message([](TalusSettings& s) { s.randomness = 1.0; }).find("randomness"),
              std::string::npos);
}

}  // namespace
}  // namespace sandtin
