#pragma once
// The branch-free passes of the talus kernel (detail::flowing_volumes) for a row of up to eight
// slots in one AVX-512 register: two divisions for the whole row, and masks instead of
// branches. Each slot takes the same operations, in the same order, as in the two-lane SSE2
// passes, and the volumes are summed in row order as there, so the results are the same bit
// for bit (talus_kernel_avx512_test compares them with the plain kernel). The caller checks
// avx512_rows_supported() once and compiles its loop for the ISA with SANDTIN_AVX512_TARGET.
// Compiled only for x86-64 GCC and Clang; elsewhere avx512_rows_supported() is false and the
// SSE2 passes run.
//
// No multiply-add may be fused here: AVX-512 has fused multiply-adds, and GCC's default in C++
// (-ffp-contract=fast) allows it to fuse vector expressions. The project builds with
// -ffp-contract=off, so every path rounds each product as the SSE2 passes and the compute
// shader do.

#include <cstdint>

#include "physics/talus_kernel.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SANDTIN_HAVE_AVX512_ROWS 1
// GCC 12 warns of an uninitialised variable inside its own AVX-512 intrinsics (the
// _mm512_undefined_pd() of their unmasked forms, GCC bug 105593); warnings inside inlined code
// follow the state at the header's lines, so the include is where to silence it.
#if defined(__clang__)
#include <immintrin.h>
#else
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
#define SANDTIN_AVX512_TARGET __attribute__((target("avx512f")))
#else
#define SANDTIN_HAVE_AVX512_ROWS 0
#define SANDTIN_AVX512_TARGET
#endif

namespace sandtin {

/// Whether this CPU (and its operating system) runs AVX-512F code. False under valgrind,
/// which does not emulate AVX-512.
inline bool avx512_rows_supported() {
#if SANDTIN_HAVE_AVX512_ROWS
    return __builtin_cpu_supports("avx512f") != 0;
#else
    return false;
#endif
}

namespace detail {

/// The widest row avx512_flowing_volumes takes.
inline constexpr std::uint32_t kAvx512RowSlots = 8;

#if SANDTIN_HAVE_AVX512_ROWS

/// Lanes [0, degree) of an 8-lane mask.
SANDTIN_AVX512_TARGET inline __mmask8 avx512_lanes(std::uint32_t degree) {
    return static_cast<__mmask8>((1u << degree) - 1u);
}

/// The sum of the eight lanes in lane order, from +0.0: the row-order sum of the scalar passes
/// (lanes past the row hold +0.0, which changes no sum of values >= +0.0). Read from the
/// register: reading lanes back from a masked store would wait for the store to retire.
SANDTIN_AVX512_TARGET inline double avx512_sum_in_order(__m512d v) {
    const __m256d low = _mm512_castpd512_pd256(v);
    const __m256d high = _mm512_extractf64x4_pd(v, 1);
    double sum = 0.0;
    for (const __m128d pair : {_mm256_castpd256_pd128(low), _mm256_extractf128_pd(low, 1),
                               _mm256_castpd256_pd128(high), _mm256_extractf128_pd(high, 1)}) {
        sum += _mm_cvtsd_f64(pair);
        sum += _mm_cvtsd_f64(_mm_unpackhi_pd(pair, pair));
    }
    return sum;
}

/// A row's levelling volumes: lane k holds q[k] of the scalar passes, +0.0 past the row.
struct Avx512Row {
    __m512d volume;
    RowExcess excess;
};

/// detail::flowing_volumes for the row [0, degree) at `target` and `length`, 1 <= degree <= 8,
/// bit for bit.
SANDTIN_AVX512_TARGET inline Avx512Row avx512_flowing_volumes(
    std::uint32_t i, std::uint32_t degree, const std::uint32_t* target, const double* length,
    const double* height, const double* area, double tan_alpha, const TalusParameters& p,
    double noise_floor) {
    const __mmask8 lanes = avx512_lanes(degree);
    const __m512d slope =
        _mm512_mul_pd(_mm512_maskz_loadu_pd(lanes, length), _mm512_set1_pd(tan_alpha));
    // The neighbours' heights and areas by scalar loads, which issue as soon as their index is
    // known (4 % faster than two gathers on Zen 4). Lanes past the row repeat its last slot,
    // so every load is in bounds; `lanes` keeps them out of every result.
    std::uint32_t t[kAvx512RowSlots];
    for (std::uint32_t k = 0; k < kAvx512RowSlots; ++k)
        t[k] = target[k < degree ? k : degree - 1];
    const __m512d h_to = _mm512_set_pd(height[t[7]], height[t[6]], height[t[5]], height[t[4]],
                                       height[t[3]], height[t[2]], height[t[1]], height[t[0]]);
    const __m512d a_to = _mm512_set_pd(area[t[7]], area[t[6]], area[t[5]], area[t[4]], area[t[3]],
                                       area[t[2]], area[t[1]], area[t[0]]);
    const __m512d e = _mm512_sub_pd(_mm512_sub_pd(_mm512_set1_pd(height[i]), h_to), slope);
    const double degenerate = kDegenerateAreaRatio * area[i];
    // (e > tol r tan) & (e > floor) & !(A_j < degenerate): ordered comparisons, as C++'s.
    const __mmask8 flows =
        _mm512_mask_cmp_pd_mask(lanes, e, _mm512_mul_pd(_mm512_set1_pd(p.rest_tolerance), slope),
                                _CMP_GT_OQ) &
        _mm512_cmp_pd_mask(e, _mm512_set1_pd(noise_floor), _CMP_GT_OQ) &
        static_cast<__mmask8>(~_mm512_cmp_pd_mask(a_to, _mm512_set1_pd(degenerate), _CMP_LT_OQ));
    const __m512d excess =
        _mm512_maskz_add_pd(flows, e, _mm512_mul_pd(_mm512_set1_pd(p.settle_margin), slope));
    const __m512d inv_ai = _mm512_set1_pd(1.0 / area[i]);
    Avx512Row out;
    out.volume = _mm512_maskz_div_pd(
        flows, excess, _mm512_add_pd(inv_ai, _mm512_div_pd(_mm512_set1_pd(1.0), a_to)));
    out.excess.levelling = avx512_sum_in_order(out.volume);
    // Every lane is >= +0.0 (no NaN: a NaN excess does not flow), so the order of the maximum
    // does not matter: halves, then pairs, then neighbours.
    __m512d largest = _mm512_max_pd(excess, _mm512_shuffle_f64x2(excess, excess, 0x4E));
    largest = _mm512_max_pd(largest, _mm512_shuffle_f64x2(largest, largest, 0xB1));
    largest = _mm512_max_pd(largest, _mm512_permute_pd(largest, 0x55));
    out.excess.largest = _mm512_cvtsd_f64(largest);
    return out;
}

/// Sends a row's levelling volumes scaled by `scale`, as the branch-free SSE2 sending does
/// (talus_solver.cpp): volume * scale into inflow[reverse[k]] where it is positive, each such
/// receiver's bit in `receive`, and the total summed in row order. Returns the total; adds
/// the number of flowing slots to `flowing`.
SANDTIN_AVX512_TARGET inline double avx512_send(__m512d volume, std::uint32_t degree, double scale,
                                                const std::uint32_t* target,
                                                const std::uint32_t* reverse, double* inflow,
                                                std::uint64_t* receive, std::size_t& flowing) {
    const __mmask8 lanes = avx512_lanes(degree);
    const __m512d sent = _mm512_mul_pd(volume, _mm512_set1_pd(scale));
    const __mmask8 flows = _mm512_mask_cmp_pd_mask(lanes, sent, _mm512_setzero_pd(), _CMP_GT_OQ);
    flowing += static_cast<std::size_t>(__builtin_popcount(flows));
    // Lane by lane through an unmasked store, which later loads of single lanes are forwarded
    // from (a scatter, or a masked store, makes the bitmap updates below wait for it).
    alignas(64) double volume_of[kAvx512RowSlots];
    _mm512_store_pd(volume_of, sent);
    for (std::uint32_t k = 0; k < degree; ++k) {
        const std::uint32_t t = target[k];
        receive[t >> 6] |= static_cast<std::uint64_t>((flows >> k) & 1u) << (t & 63u);
        inflow[reverse[k]] = volume_of[k];  // +0.0 where nothing flows: the slot holds +0.0
    }
    return avx512_sum_in_order(sent);
}

/// talus_outflow for a row of 1 to 8 slots without a relocation radius, in AVX-512: writes
/// q[0, degree) (m³) and returns their total, bit for bit as talus_outflow does. What the
/// tests compare with the plain kernel; the Jacobi schedule sends as it scales instead
/// (avx512_send).
SANDTIN_AVX512_TARGET inline double avx512_talus_outflow(std::uint32_t i, std::uint32_t degree,
                                                         const std::uint32_t* target,
                                                         const double* length, const double* height,
                                                         const double* area, const double* bedrock,
                                                         double tan_alpha, const TalusParameters& p,
                                                         double share, double* q) {
    const double hi = height[i];
    const Avx512Row row = avx512_flowing_volumes(i, degree, target, length, height, area, tan_alpha,
                                                 p, excess_floor(hi));
    double scale = 0.0;
    if (row.excess.largest > 0.0)
        scale = outflow_scale(row.excess, hi, area[i], bedrock[i], p, share);
    if (!(scale > 0.0)) scale = 0.0;  // +0.0 * every volume: q is +0.0 throughout
    const __m512d sent = _mm512_mul_pd(row.volume, _mm512_set1_pd(scale));
    _mm512_mask_storeu_pd(q, avx512_lanes(degree), sent);
    return avx512_sum_in_order(sent);
}

#endif

}  // namespace detail
}  // namespace sandtin
