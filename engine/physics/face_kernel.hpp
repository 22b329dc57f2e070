#pragma once
// The per-vertex step of talus relaxation under the face rule (SlopeRule::Face): at rest every
// triangle's gradient satisfies |grad h| <= tan(alpha), not only every edge's slope (issue 39;
// Prigozhin's variational sandpile, and the local triangle update of fast marching, Kimmel &
// Sethian 1998).
//
// For vertex i and each face (i, j, l) of its row (physics/adjacency_graph.hpp's across()),
// with the other two corners' heights fixed, the highest i may stand is
//   b = h(p) + d sqrt(T^2 - g_t^2),
// p the foot of the altitude from i onto the line jl, d that altitude, g_t the slope along jl
// and T = tan(alpha_i): the plane through the three corners then has |grad h| = T exactly.
// Where h_i > b, sand leaves i down that plane's steepest-descent line, which crosses the line
// jl at the point c: j and l receive the shares 1 - t and t of c's position t along jl
// (clamped to the edge). The volume that levels the face alone is e / (1/A_i + w_j^2/A_j +
// w_l^2/A_l): raising j and l raises b by about the height they add at c; each receiver takes
// at most what would level it with i alone (a small corner with a small share would otherwise
// be raised far above i, send it back, and the relaxation would never rest). A corner higher than i
// receives nothing (the other takes all), so sand never climbs; where the opposite edge
// is itself steeper than repose (|g_t| >= T) no plane through j and l is at repose, and the
// face falls back to the edge rule towards its lower far corner.
//
// Everything else is the edge rule's (talus_kernel.hpp): volume form, the levelling share and the
// cap on i's drop, the sand above the bedrock, the settle margin (faces trigger above T and level
// towards (1 - m) T), the rest tolerance (relative to each face's altitude, so slivers are
// judged on their own scale), degenerate receivers, the relocation radius, the jitter. The
// shares of the faces that send to one neighbour add up in its slot, so both schedules apply
// them as they apply edges': the sequential one at once, the Jacobi one (TalusSolver) from
// the heights at the start of the iteration, through the same per-slot inflow. The Jacobi
// schedule's branch-free and AVX-512 row passes are the edge rule's only; face rows branch.
// shaders/talus_face_outflow.comp transcribes face_shed and face_row_scale in float.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "physics/talus_kernel.hpp"

namespace sandtin {

/// Corner i's view of its face (i, j, l), with |ij| = a, |il| = b, |jl| = c (m): the foot of
/// the altitude from i onto the line jl, as a fraction of |jl| from j (it may fall outside
/// [0, 1]), and the altitude (m), 0 when i lies on the line jl (no plane to judge) or there is
/// no face (c == 0). It depends on the plan only, so the graph keeps one per slot
/// (AdjacencyGraph::face_rows) and a row's faces pay no division or root for their shape.
struct FaceCorner {
    double foot = 0.0;
    double altitude = 0.0;
};

inline FaceCorner face_corner(double a, double b, double c) {
    if (!(c > 0.0)) return {};
    const double dj = (a * a + c * c - b * b) / (2.0 * c);  // foot of the altitude, from j
    const double alt2 = a * a - dj * dj;
    if (!(alt2 > 1e-14 * a * a)) return {};
    return {dj / c, std::sqrt(alt2)};
}

/// A graph's faces, slot by slot: the across length (AdjacencyGraph::across) and the corner's
/// shape (face_corner of the slot's and the next slot's lengths and the across length), or no
/// shapes (null: a graph that keeps none, FaceShapes::Skip; the kernel works them out).
struct FaceRows {
    const double* across = nullptr;
    const FaceCorner* corner = nullptr;
    /// The same rows seen from slot k (a kernel that indexes a row from 0).
    FaceRows from(std::uint32_t k) const {
        return {across + k, corner != nullptr ? corner + k : nullptr};
    }
};

namespace detail {

/// One face's excess (m, at the settle margin) and its receivers' shares, or nothing.
struct FaceShed {
    double excess = 0.0;  ///< > 0 when the face sheds
    double to_j = 0.0, to_l = 0.0;
    /// j (or, with `j_refuses` false, l) takes nothing: the other corner takes its share.
    void refuse(bool j_refuses) {
        double& from = j_refuses ? to_j : to_l;
        (j_refuses ? to_l : to_j) += from;
        from = 0.0;
    }
};

/// The face (i, j, l): |ij| = a, |il| = b, |jl| = c (m), i's corner (face_corner(a, b, c)),
/// heights hi, hj, hl (m). Always inlined: GCC kept it out of line in the row loops, and the
/// call, with its result through memory, cost 12 % of the face rule's Jacobi throughput on 10⁶
/// vertices (5.3 -> 6.0 M updates/s, the same results bit for bit).
[[gnu::always_inline]] inline FaceShed face_shed(FaceCorner corner, double a, double b, double c,
                                                 double hi, double hj, double hl, double tan_alpha,
                                                 const TalusParameters& p, double floor) {
    FaceShed out;
    const double alt = corner.altitude;
    if (!(alt > 0.0)) return out;  // i on the line jl: no plane to judge
    const double s = corner.foot;
    const double gt = (hl - hj) / c;
    if (std::abs(gt) < tan_alpha) {
        const double at_foot = hj + s * (hl - hj);
        const double trigger = hi - (at_foot + alt * std::sqrt(tan_alpha * tan_alpha - gt * gt));
        if (!(trigger > p.rest_tolerance * alt * tan_alpha) || !(trigger > floor)) return out;
        // Levelled towards (1 - m) T where a plane through j and l can be that gentle, else
        // towards T itself (the opposite edge is between the two).
        const double margin_tan = (1.0 - p.settle_margin) * tan_alpha;
        const double level_tan = std::abs(gt) < margin_tan ? margin_tan : tan_alpha;
        const double w = std::sqrt(level_tan * level_tan - gt * gt);
        out.excess = hi - (at_foot + alt * w);
        // Where the steepest-descent line of the levelled plane meets the line jl.
        const double t = std::clamp(s - gt * alt / (w * c), 0.0, 1.0);
        out.to_j = 1.0 - t;
        out.to_l = t;
    } else {
        // The opposite edge is steeper than repose: the edge rule towards the lower corner.
        const bool to_j = hj <= hl;
        const double r = to_j ? a : b;
        const double e = hi - (to_j ? hj : hl) - r * tan_alpha;
        if (!(e > p.rest_tolerance * r * tan_alpha) || !(e > floor)) return out;
        out.excess = e + p.settle_margin * r * tan_alpha;
        out.to_j = to_j ? 1.0 : 0.0;
        out.to_l = to_j ? 0.0 : 1.0;
    }
    // Sand never climbs: a corner above i takes no share.
    if (hj >= hi) out.refuse(true);
    if (hl >= hi) out.refuse(false);
    if (!(out.to_j + out.to_l > 0.0)) out.excess = 0.0;
    return out;
}

/// face_shed with i's corner worked out here (tests; the kernels read the graph's).
inline FaceShed face_shed(double a, double b, double c, double hi, double hj, double hl,
                          double tan_alpha, const TalusParameters& p, double floor) {
    return face_shed(face_corner(a, b, c), a, b, c, hi, hj, hl, tan_alpha, p, floor);
}

}  // namespace detail

/// talus_row_scale under the face rule: writes q[k] (m³) for every slot of i's row, the volume
/// that would level the faces that send to target[k] alone, and returns the factor s that
/// scales them all (0 exactly when nothing leaves; every q[k] is +0.0 then). `faces` is the
/// graph's face_rows() (see physics/adjacency_graph.hpp).
template <bool kRelocation, class NeedsSplit>
inline double face_row_scale(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                             const std::uint32_t* target, const double* length, FaceRows faces,
                             const double* longest, const double* height, const double* area,
                             const double* bedrock, double tan_alpha, const TalusParameters& p,
                             double share, double* q, NeedsSplit&& needs_split) {
    const std::uint32_t end = begin + degree;
    const double hi = height[i];
    const double floor = detail::excess_floor(hi);
    const double r_limit = p.relocation_radius > 0.0 ? p.relocation_radius * (1.0 + 1e-9) : 1e300;
    const double inv_ai = 1.0 / area[i];
    const double degenerate = kDegenerateAreaRatio * area[i];
    for (std::uint32_t k = begin; k < end; ++k)
        q[k] = 0.0;
    detail::RowExcess excess;
    for (std::uint32_t k = begin; k < end; ++k) {
        const double c = faces.across[k];
        if (!(c > 0.0)) continue;
        const std::uint32_t kn = k + 1 == end ? begin : k + 1;
        const std::uint32_t j = target[k], l = target[kn];
        const FaceCorner corner =
            faces.corner != nullptr ? faces.corner[k] : face_corner(length[k], length[kn], c);
        detail::FaceShed f = detail::face_shed(corner, length[k], length[kn], c, hi, height[j],
                                               height[l], tan_alpha, p, floor);
        if (!(f.excess > 0.0)) continue;
        if constexpr (kRelocation) {
            if (length[k] > r_limit || length[kn] > r_limit) {
                needs_split(i);
                continue;
            }
            if (longest[j] > r_limit || longest[l] > r_limit) {
                needs_split(longest[j] > r_limit ? j : l);
                continue;
            }
        }
        // A degenerate receiver passes its share to the other, or the face sheds nothing.
        if (area[j] < degenerate) f.refuse(true);
        if (area[l] < degenerate) f.refuse(false);
        if (!(f.to_j + f.to_l > 0.0)) continue;
        const double denominator = inv_ai + (f.to_j > 0.0 ? f.to_j * f.to_j / area[j] : 0.0) +
                                   (f.to_l > 0.0 ? f.to_l * f.to_l / area[l] : 0.0);
        // Each receiver takes at most what would bring it level with i alone (the edge rule's
        // levelling volume): a corner with a small share and a small area would otherwise be
        // raised far above i, send it back, and the relaxation would never rest.
        const double volume = f.excess / denominator;
        const double to_j = f.to_j > 0.0 ? std::min(f.to_j * volume, std::max(0.0, hi - height[j]) /
                                                                         (inv_ai + 1.0 / area[j]))
                                         : 0.0;
        const double to_l = f.to_l > 0.0 ? std::min(f.to_l * volume, std::max(0.0, hi - height[l]) /
                                                                         (inv_ai + 1.0 / area[l]))
                                         : 0.0;
        if (!(to_j + to_l > 0.0)) continue;
        q[k] += to_j;
        q[kn] += to_l;
        excess.levelling += to_j + to_l;
        excess.largest = std::max(excess.largest, f.excess);
    }
    if (!(excess.largest > 0.0)) return 0.0;
    const double scale = detail::outflow_scale(excess, hi, area[i], bedrock[i], p, share);
    // A drop of i within the noise floor is rounding, not sand: sand left a few ulps above
    // the bedrock on rock steeper than repose (every face of i stays steep however little sand
    // it holds) would otherwise trickle on for ever (measured on thin sand over 56° rock: 43
    // vertices trading 3e-16 m³ per 5 000 iterations, never at rest).
    if (!(scale > 0.0) || !(scale * excess.levelling * inv_ai > floor)) {
        for (std::uint32_t k = begin; k < end; ++k)
            q[k] = 0.0;
        return 0.0;
    }
    return scale;
}

/// face_row_scale with the relocation radius chosen at run time (talus_scale's twin; the
/// Jacobi schedule scales as it sends).
template <class NeedsSplit>
inline double face_scale(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                         const std::uint32_t* target, const double* length, FaceRows faces,
                         const double* longest, const double* height, const double* area,
                         const double* bedrock, double tan_alpha, const TalusParameters& p,
                         double share, double* q, NeedsSplit&& needs_split) {
    if (p.relocation_radius > 0.0)
        return face_row_scale<true>(i, begin, degree, target, length, faces, longest, height, area,
                                    bedrock, tan_alpha, p, share, q, needs_split);
    return face_row_scale<false>(i, begin, degree, target, length, faces, longest, height, area,
                                 bedrock, tan_alpha, p, share, q, needs_split);
}

/// talus_outflow under the face rule: q[k] (m³) for every slot, and their total.
template <class NeedsSplit>
inline double face_outflow(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                           const std::uint32_t* target, const double* length, FaceRows faces,
                           const double* longest, const double* height, const double* area,
                           const double* bedrock, double tan_alpha, const TalusParameters& p,
                           double share, double* q, NeedsSplit&& needs_split) {
    const double scale = face_scale(i, begin, degree, target, length, faces, longest, height, area,
                                    bedrock, tan_alpha, p, share, q, needs_split);
    if (scale == 0.0) return 0.0;
    double sent = 0.0;
    for (std::uint32_t k = begin; k < begin + degree; ++k) {
        q[k] *= scale;
        sent += q[k];
    }
    return sent;
}

}  // namespace sandtin
