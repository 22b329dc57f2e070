#pragma once
// The per-vertex step of talus relaxation (seed 000 §7.2 Eqs. 7.4-7.5, seed 003 §3.2), in
// volume form so that mass is conserved exactly. Shared by the sequential schedule, the Jacobi
// schedule and (transcribed) the compute shader, so all three do the same arithmetic.
//
// For vertex i with lumped area A_i and each neighbour j at horizontal distance r_ij, the
// excess over the angle of repose is e_ij = (h_i - h_j) - r_ij tan(alpha_i). Moving volume q
// from i to j lowers that step by q (1/A_i + 1/A_j), so q*_ij = e_ij / (1/A_i + 1/A_j) would
// remove it exactly were j the only lower neighbour. Each edge gets the share
//   q_ij = sigma * q*_ij * s,   s = min(1, damping E A_i / (sigma sum_j q*_ij)),  E = max_j e_ij,
// so no edge moves more than sigma <= 1 times what levels it, and i itself drops by at most
// damping * E (the seeds' "half the largest height difference", Eq. 7.4); when the cap binds,
// the shares are proportional to q*_ij (the seeds' Eq. 7.5 in volume form). sigma is the
// schedule's levelling share (times the jitter, and never above 1): the sequential schedule
// levels each edge whole (sigma = 1), since every receiver's height is current when the next
// vertex looks at it; the Jacobi schedule (and the compute shader) sends damping times it
// (sigma = damping), since a receiver there takes from all its senders at once and each
// levels against its old height. The cap on i's drop is the same in both, so the worst
// overshoot of an edge (i dropping by damping E for an edge whose own excess was small) is
// too: sigma = 1 only lets an edge whose vertex has room under the cap level in one step
// instead of halving. Measured on the 10^4 groove to rest (sequential, face rule): 625 -> 476
// iterations, 1 018 298 -> 725 730 vertex updates. Raising the cap instead overshot: damping 1
// rested that groove in 225 iterations but left runs that never rested, damping 0.75 rested
// piles 4-5 % low. A small
// neighbour only limits its own edge: a per-vertex budget shared by excess would let one
// sliver vertex throttle the whole neighbourhood. The outflow is capped by the sand above the
// bedrock, A_i (h_i - b_i). Edges longer than the relocation radius carry nothing; they are
// reported so the caller can split them (seed 000 §7.2, "prevention of long edges").
//
// Settling margin m (default 0.03): an edge starts to flow when e > tol r tan(alpha), as before,
// but a flowing edge is levelled towards (1 - m) r tan(alpha), not r tan(alpha). Sand that
// moves comes to rest a little below the angle it can stand at (the dynamic angle of repose
// is 1-3 degrees below the angle of maximum stability; Jaeger, Nagel & Behringer, Rev. Mod.
// Phys. 68 (1996) §II). Without it, an avalanche leaves its whole slope exactly at the
// threshold, and every later grain that arrives re-triggers the slope below it: measured
// after a dig into a slope 3 % under repose (edge rule), a creep of tens of vertices trading
// 1e-11 m³ for 16 174 (sequential) and 42 140 (Jacobi) iterations; m = 0.03 rests in 1 443 and
// 4 232 (the face rule: 1 288 and 2 156 without the margin, 805 and 1 369 with it).
// Neither the trigger nor the bound "no edge steeper than (1 + tol) tan(alpha)" changes.
//
// Degenerate receivers: an edge into a vertex whose lumped area is below kDegenerateAreaRatio
// of the sender's carries nothing. Levelling it moves q* = e / (1/A_i + 1/A_j) ~ e A_j, so the
// sender drops by at most 1e-6 of the excess per iteration: the transfer never completes, it
// only creeps. Such vertices are the corners of triangles with no area in the plane (a
// vertical sliver between constraints a hair apart); they hold no sand, and pass on at once
// whatever they get. The stamp used to leave them where a box or the λ is stroked along a
// straight side (428 after the λ groove at 10^4 points, with 1 456 vertices trading 1.1e-12 m³
// per iteration through them, unchanged after 10^5 iterations: the terrain never rested). It
// no longer does (Tin::release_constraints), but any terrain may hold some, so the rule
// stays. Edges out of them, and between them, flow as usual, so they drain and rest too.

#include <algorithm>
#include <bit>
#include <cstdint>

namespace sandtin {

/// An edge into a vertex with less than this fraction of the sender's lumped area carries
/// nothing (see above). Real neighbours are far from it: the smallest ratio measured was 1.1e-3
/// (a random 10^6-point TIN; the shipped tools' grooves at 10^4 points: 1.7e-3 and up).
inline constexpr double kDegenerateAreaRatio = 1e-6;
/// The largest settle margin the editor and scripts offer (the solver accepts up to 1).
inline constexpr double kMaxSettleMargin = 0.2;

/// What the relaxation holds at the angle of repose (issue 39).
enum class SlopeRule : std::uint8_t {
    /// Every edge: h_i - h_j <= r_ij tan(alpha) (seed 000 §7.2). A triangle can still be far
    /// steeper than all three of its edges.
    Edge,
    /// Every triangle: |grad h| <= tan(alpha), the piecewise-linear surface itself (Prigozhin's
    /// critical-slope model; physics/face_kernel.hpp). Both schedules; its Jacobi rows take
    /// the branching passes only.
    Face,
};

struct TalusParameters {
    /// The cap on a vertex's drop per step, as a fraction of its largest excess (seeds: 1/2);
    /// the Jacobi schedule also sends only this fraction of each edge's levelling volume.
    double damping = 0.5;
    double rest_tolerance = 1e-4;    ///< an edge is at rest when e <= tol * r tan(alpha)
    double relocation_radius = 0.0;  ///< r_S in metres; 0 = no limit
    /// m in [0, 1): flowing edges level towards (1 - m) r tan(alpha) (see above); 0 = the
    /// seeds' rule. The compute shader does the same. The default is the editor's and the
    /// scripts' alike, so a script reproduces what the artist saw.
    double settle_margin = 0.03;
    /// The face rule is the default everywhere (editor, scripts, haptics, stress): a rested
    /// pile then has no triangle steeper than its sand can stand. The edge rule stays for
    /// comparison and old scripts ("rule": "edge").
    SlopeRule rule = SlopeRule::Face;
};

/// Splitmix64 hash to [-1, 1): a deterministic per-vertex, per-iteration random number.
inline double signed_unit_hash(std::uint64_t seed, std::uint64_t vertex, std::uint64_t iteration) {
    std::uint64_t z = seed ^ (vertex * 0x9E3779B97F4A7C15ull) ^ (iteration * 0xD1B54A32D192ED03ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/// How the passes over a row run. Both give the same results bit for bit (a test compares them
/// with a plain reference); they differ in which terrain they are fast on.
enum class RowPasses {
    /// A branch per slot: cheapest where few edges flow and the branches predict well, as on
    /// a terrain coming to rest. The sequential schedule always runs these.
    Branching,
    /// No branch per slot, two slots per SSE2 operation (in the Jacobi schedule, a whole row of
    /// up to eight per AVX-512 operation where the CPU has it: talus_kernel_avx512.hpp): for
    /// an active terrain, where whether an edge flows is a coin toss and mispredicted branches
    /// cost more than the arithmetic.
    /// The Jacobi schedule picks these when enough of its slots flowed in the iteration before
    /// (TalusSolver: 10⁶ active vertices relax a quarter faster). Without a relocation radius
    /// only; with one, the rows branch. (Listing the flowing slots instead, so that the later
    /// passes visit only those, measured slower on both kinds of terrain.)
    BranchFree,
};

namespace detail {

/// Two doubles in one SSE2 register (GCC and Clang vector extensions), and a lane mask.
using DoublePair = double __attribute__((vector_size(16)));
using LaneMask = std::int64_t __attribute__((vector_size(16)));

/// Each lane of `value` where `keep` is set, else +0.0.
inline DoublePair keep_lanes(LaneMask keep, DoublePair value) {
    return std::bit_cast<DoublePair>(std::bit_cast<LaneMask>(value) & keep);
}

/// `value` when `keep`, else +0.0, without a branch.
inline double select_or_zero(bool keep, double value) {
    const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(keep);
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(value) & mask);
}

struct RowExcess {
    /// The largest excess of a flowing slot (m), 0 when none flows. A flowing slot's excess is
    /// positive (e > 0, and the margin adds m r tan(alpha) >= 0), so this alone tells whether
    /// anything flows.
    double largest = 0.0;
    double levelling = 0.0;  ///< of the levelling volumes, in row order (m³)
};

/// The passes of RowPasses::BranchFree, in one: q[k] = the volume that levels each flowing
/// slot alone, e / (1/A_i + 1/A_j), +0.0 elsewhere (changing no sum). Two slots at a time in
/// SSE2 lanes: the largest excess does not depend on the order, so it may be taken lane by
/// lane; the levelling sum is taken in row order, as the branching passes take it. Every slot
/// pays its two divisions, flowing or not: a packed division costs what a scalar one does, and
/// this runs where most slots flow.
inline RowExcess flowing_volumes(std::uint32_t i, std::uint32_t begin, std::uint32_t end,
                                 const std::uint32_t* target, const double* length,
                                 const double* height, const double* area, double tan_alpha,
                                 const TalusParameters& p, double noise_floor, double* q) {
    const double hi = height[i];
    const double inv_ai = 1.0 / area[i];
    const double degenerate = kDegenerateAreaRatio * area[i];
    const DoublePair hi2 = {hi, hi}, tan2 = {tan_alpha, tan_alpha};
    const DoublePair tol2 = {p.rest_tolerance, p.rest_tolerance};
    const DoublePair margin2 = {p.settle_margin, p.settle_margin};
    const DoublePair floor2 = {noise_floor, noise_floor}, degenerate2 = {degenerate, degenerate};
    const DoublePair inv_ai2 = {inv_ai, inv_ai}, ones = {1.0, 1.0};
    DoublePair largest2 = {0.0, 0.0};
    double levelling = 0.0;
    std::uint32_t k = begin;
    for (; k + 1 < end; k += 2) {
        const DoublePair slope = DoublePair{length[k], length[k + 1]} * tan2;
        const std::uint32_t t0 = target[k], t1 = target[k + 1];
        const DoublePair to = {area[t0], area[t1]};
        const DoublePair e = (hi2 - DoublePair{height[t0], height[t1]}) - slope;
        const LaneMask flows = (e > tol2 * slope) & (e > floor2) & ~(to < degenerate2);
        const DoublePair excess = keep_lanes(flows, e + margin2 * slope);
        largest2 = largest2 > excess ? largest2 : excess;  // a lane-wise max (one MAXPD)
        const DoublePair volume = keep_lanes(flows, excess / (inv_ai2 + ones / to));
        q[k] = volume[0];
        q[k + 1] = volume[1];
        levelling += volume[0];
        levelling += volume[1];
    }
    RowExcess out{std::max(largest2[0], largest2[1]), levelling};
    if (k < end) {
        const double slope = length[k] * tan_alpha;
        const std::uint32_t t = target[k];
        const double e = (hi - height[t]) - slope;
        const bool flows =
            (e > p.rest_tolerance * slope) & (e > noise_floor) & !(area[t] < degenerate);
        const double excess = select_or_zero(flows, e + p.settle_margin * slope);
        out.largest = std::max(out.largest, excess);
        q[k] = select_or_zero(flows, excess / (inv_ai + 1.0 / area[t]));
        out.levelling += q[k];
    }
    return out;
}

/// The end of talus_row_scale, once a row's excess is known and flows (excess.largest > 0):
/// the factor s for the row's levelling volumes, of vertex i with height hi (m), lumped area
/// area_i (m²) and bedrock bedrock_i (m), with the step's levelling share `share` (the
/// schedule's sigma times the jitter; above 1 it is taken as 1, so no edge carries more than
/// levels it). Not positive when no sand lies above the bedrock.
inline double outflow_scale(const RowExcess& excess, double hi, double area_i, double bedrock_i,
                            const TalusParameters& p, double share) {
    const double levelling = excess.levelling;
    double scale = std::min(share, 1.0);
    const double cap = p.damping * excess.largest * area_i;
    if (scale * levelling > cap) scale = cap / levelling;
    const double available = area_i * (hi - bedrock_i);
    if (scale * levelling > available) scale = std::max(available, 0.0) / levelling;
    return scale;
}

/// Below a few ulps of the height hi an "excess" is rounding noise; acting on it would make
/// two nearly coincident vertices trade the last bit forever.
inline double excess_floor(double hi) {
    return 64.0 * 2.220446049250313e-16 * (hi < 0.0 ? -hi : hi);
}

}  // namespace detail

/// The first part of talus_outflow: writes q[k] (m³), the volume that would level each
/// flowing slot of the row alone, and returns the factor s that the outflow scales them all by
/// (damping, the cap on the vertex's drop and the sand above the bedrock; see above). Returns 0
/// exactly when nothing leaves, and every q[k] is +0.0 then. Callers that visit the row again
/// anyway (the Jacobi schedule's distribution) scale as they go; talus_outflow scales here.
template <bool kRelocation, RowPasses kPasses, class NeedsSplit>
inline double talus_row_scale(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                              const std::uint32_t* target, const double* length,
                              const double* longest, const double* height, const double* area,
                              const double* bedrock, double tan_alpha, const TalusParameters& p,
                              double share, double* q, NeedsSplit&& needs_split) {
    constexpr bool kBranchFree = !kRelocation && kPasses == RowPasses::BranchFree;
    const double hi = height[i];
    const std::uint32_t end = begin + degree;
    const double floor = detail::excess_floor(hi);
    detail::RowExcess excess;
    if constexpr (kBranchFree) {
        (void)longest;
        (void)needs_split;
        excess = detail::flowing_volumes(i, begin, end, target, length, height, area, tan_alpha, p,
                                         floor, q);
        if (!(excess.largest > 0.0)) return 0.0;
    } else {
        const double r_limit =
            p.relocation_radius > 0.0 ? p.relocation_radius * (1.0 + 1e-9) : 1e300;
        for (std::uint32_t k = begin; k < end; ++k) {
            const double r = length[k];
            const double slope = r * tan_alpha;
            const double e = (hi - height[target[k]]) - slope;
            q[k] = 0.0;
            if (!(e > p.rest_tolerance * slope) || !(e > floor)) continue;
            if constexpr (kRelocation) {
                if (r > r_limit) {
                    needs_split(i);
                    continue;
                }
                if (longest[target[k]] > r_limit) {
                    needs_split(target[k]);
                    continue;
                }
            }
            if (area[target[k]] < kDegenerateAreaRatio * area[i]) continue;  // degenerate receiver
            q[k] = e + p.settle_margin * slope;  // the excess (== e when m = 0), for now
            excess.largest = std::max(excess.largest, q[k]);
        }
        if (!(excess.largest > 0.0)) return 0.0;
        // Now turn each excess into the volume that levels its edge alone.
        const double inv_ai = 1.0 / area[i];
        for (std::uint32_t k = begin; k < end; ++k) {
            if (q[k] > 0.0) {
                q[k] = q[k] / (inv_ai + 1.0 / area[target[k]]);
                excess.levelling += q[k];
            }
        }
    }
    const double scale = detail::outflow_scale(excess, hi, area[i], bedrock[i], p, share);
    if (!(scale > 0.0)) {  // no sand above the bedrock: nothing leaves
        for (std::uint32_t k = begin; k < end; ++k)
            q[k] = 0.0;
        return 0.0;
    }
    return scale;
}

/// talus_row_scale with the relocation radius chosen at run time.
template <RowPasses kPasses = RowPasses::Branching, class NeedsSplit>
inline double talus_scale(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                          const std::uint32_t* target, const double* length, const double* longest,
                          const double* height, const double* area, const double* bedrock,
                          double tan_alpha, const TalusParameters& p, double share, double* q,
                          NeedsSplit&& needs_split) {
    if (p.relocation_radius > 0.0)
        return talus_row_scale<true, kPasses>(i, begin, degree, target, length, longest, height,
                                              area, bedrock, tan_alpha, p, share, q, needs_split);
    return talus_row_scale<false, kPasses>(i, begin, degree, target, length, longest, height, area,
                                           bedrock, tan_alpha, p, share, q, needs_split);
}

/// Computes the outflow of vertex i along its row [begin, begin + degree) of the graph. Writes
/// q[k] (m³) for every slot of the row, and returns the total, which is exactly the sum of the
/// q[k] written (so what leaves equals what arrives). With a relocation radius r_S, an edge
/// longer than r_S (by more than rounding) carries nothing, and neither does an edge to a
/// vertex that has such an edge (its gain would spread over the long triangles); the vertex
/// to refine around is passed to `needs_split` and the edge flows once it is split.
/// `longest` holds each vertex's longest edge (m). Without a relocation radius the long-edge
/// tests, and the load of each neighbour's longest edge, are compiled out (talus_row_scale's
/// kRelocation). kPasses: see RowPasses.
template <RowPasses kPasses = RowPasses::Branching, class NeedsSplit>
inline double talus_outflow(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                            const std::uint32_t* target, const double* length,
                            const double* longest, const double* height, const double* area,
                            const double* bedrock, double tan_alpha, const TalusParameters& p,
                            double share, double* q, NeedsSplit&& needs_split) {
    const double scale = talus_scale<kPasses>(i, begin, degree, target, length, longest, height,
                                              area, bedrock, tan_alpha, p, share, q, needs_split);
    if (scale == 0.0) return 0.0;
    double sent = 0.0;
    for (std::uint32_t k = begin; k < begin + degree; ++k) {
        q[k] *= scale;  // +0.0 * scale adds +0.0: no need to branch
        sent += q[k];
    }
    return sent;
}

}  // namespace sandtin
