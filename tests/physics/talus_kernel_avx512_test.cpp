// The AVX-512 rows of the talus kernel (engine/physics/talus_kernel_avx512.hpp) against the
// plain kernel written from the definition (reference_talus_kernel.hpp): the same volumes and
// the same total bit for bit, on random rows of every width they take (1 to 8 slots), with
// bedrock, levelling shares, settle margins, exact ties, tiny and degenerate receivers. Skipped,
// saying so, on a CPU without AVX-512 (the SSE2 rows are tested in talus_kernel_test.cpp).

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "physics/talus_kernel_avx512.hpp"
#include "reference_talus_kernel.hpp"

namespace sandtin {
namespace {

TEST(TalusKernelAvx512, MatchesThePlainKernelBitForBit) {
    if (!avx512_rows_supported()) GTEST_SKIP() << "this CPU does not run AVX-512F";
#if SANDTIN_HAVE_AVX512_ROWS
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    constexpr std::uint32_t kVertices = 64;
    std::size_t flowing_rows = 0;
    std::vector<std::size_t> flowing_by_width(detail::kAvx512RowSlots + 1, 0);
    for (int trial = 0; trial < 40000; ++trial) {
        const auto degree = static_cast<std::uint32_t>(1 + rng() % detail::kAvx512RowSlots);
        std::vector<std::uint32_t> target(degree);
        std::vector<double> length(degree);
        std::vector<double> height(kVertices), area(kVertices), bedrock(kVertices);
        for (std::uint32_t v = 0; v < kVertices; ++v) {
            height[v] = u(rng) < 0.1 ? 0.3 : 0.3 * u(rng) - 0.1;  // some exact ties
            const double kind = u(rng);
            area[v] = kind < 0.1 ? 1e-6 : kind < 0.15 ? 1e-13 : 1e-4 * (0.1 + u(rng));
            bedrock[v] = u(rng) < 0.3 ? height[v] - 0.01 * u(rng) : -1.0;
        }
        for (std::uint32_t k = 0; k < degree; ++k) {
            target[k] = 1 + static_cast<std::uint32_t>(rng() % (kVertices - 1));
            length[k] = 0.001 + 0.015 * u(rng);
        }
        TalusParameters p;
        p.settle_margin = trial % 4 == 0 ? 0.05 : trial % 4 == 1 ? 0.0 : 0.03;
        p.rest_tolerance = trial % 5 == 0 ? 0.0 : 1e-4;
        p.damping = trial % 7 == 0 ? 1.0 : 0.5;
        const double tan_alpha = 0.3 + 0.5 * u(rng);
        // The levelling share: the Jacobi schedule's (damping, jittered), or the sequential
        // schedule's whole levelling, jittered past 1 (taken as 1) in some trials.
        const double share =
            trial % 3 == 0 ? 1.0 : (trial % 3 == 1 ? 0.5 : 1.0) * (0.7 + 0.6 * u(rng));
        // Lanes past the row must be left alone: sentinels on both sides.
        std::vector<double> q_ref(degree, -2.0);
        std::vector<double> q(degree + 2, -1.0);
        const std::vector<double> longest(kVertices, 0.0);  // read only with a relocation radius
        const double sent_ref = test::reference_talus_outflow(
            0, 0, degree, target.data(), length.data(), longest.data(), height.data(), area.data(),
            bedrock.data(), tan_alpha, p, share, q_ref.data(), [](std::uint32_t) {});
        const double sent = detail::avx512_talus_outflow(0, degree, target.data(), length.data(),
                                                         height.data(), area.data(), bedrock.data(),
                                                         tan_alpha, p, share, q.data() + 1);
        SCOPED_TRACE(::testing::Message() << "trial " << trial << ", " << degree << " slots");
        EXPECT_EQ(std::memcmp(&sent, &sent_ref, sizeof(double)), 0)
            << sent << " against " << sent_ref;
        EXPECT_EQ(std::memcmp(q.data() + 1, q_ref.data(), degree * sizeof(double)), 0);
        EXPECT_EQ(q.front(), -1.0);
        EXPECT_EQ(q.back(), -1.0);
        if (HasFailure()) return;  // one failing trial says it all
        if (sent_ref > 0.0) {
            ++flowing_rows;
            ++flowing_by_width[degree];
        }
    }
    // The trials really exercise flow, at every width.
    EXPECT_GT(flowing_rows, 10000u);
    for (std::uint32_t width = 1; width <= detail::kAvx512RowSlots; ++width)
        EXPECT_GT(flowing_by_width[width], 300u) << width << " slots";
#endif
}

}  // namespace
}  // namespace sandtin
