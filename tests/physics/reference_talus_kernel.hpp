#pragma once
// The talus kernel as it was first written (engine/physics/talus_kernel.hpp before it was
// specialised for speed): the reference the production kernel must match bit for bit, in
// the kernel test and inside the Jacobi schedule's reference. Plain loops straight from the
// definition; do not optimise.

#include <algorithm>
#include <cstdint>

#include "physics/talus_kernel.hpp"

namespace sandtin::test {

/// Computes the outflow of vertex i along its row [begin, begin + degree) of the graph. Writes
/// q[k] (m³) for every slot of the row, and returns the total, which is exactly the sum of the
/// q[k] written (so what leaves equals what arrives). With a relocation radius r_S, an edge
/// longer than r_S (by more than rounding) carries nothing, and neither does an edge to a
/// vertex that has such an edge (its gain would spread over the long triangles); the vertex
/// to refine around is passed to `needs_split` and the edge flows once it is split.
/// `longest` holds each vertex's longest edge (m).
template <class NeedsSplit>
inline double reference_talus_outflow(std::uint32_t i, std::uint32_t begin, std::uint32_t degree,
                                      const std::uint32_t* target, const double* length,
                                      const double* longest, const double* height,
                                      const double* area, const double* bedrock, double tan_alpha,
                                      const TalusParameters& p, double share, double* q,
                                      NeedsSplit&& needs_split) {
    const double hi = height[i];
    double largest = 0.0;
    double sum = 0.0;
    // Below a few ulps of the height an "excess" is rounding noise; acting on it would make
    // two nearly coincident vertices trade the last bit forever.
    const double floor = 64.0 * 2.220446049250313e-16 * (hi < 0.0 ? -hi : hi);
    const double r_limit = p.relocation_radius > 0.0 ? p.relocation_radius * (1.0 + 1e-9) : 1e300;
    for (std::uint32_t k = begin; k < begin + degree; ++k) {
        const double r = length[k];
        const double slope = r * tan_alpha;
        const double e = (hi - height[target[k]]) - slope;
        q[k] = 0.0;
        if (!(e > p.rest_tolerance * slope) || !(e > floor)) continue;
        if (r > r_limit) {
            needs_split(i);
            continue;
        }
        if (longest[target[k]] > r_limit) {
            needs_split(target[k]);
            continue;
        }
        // A receiver with under a millionth of the sender's lumped area (a vertical sliver)
        // takes nothing.
        if (area[target[k]] < 1e-6 * area[i]) continue;
        const double excess = e + p.settle_margin * slope;  // == e when m = 0
        q[k] = excess;                                      // for now; scaled to volume below
        sum += excess;
        largest = std::max(largest, excess);
    }
    if (!(sum > 0.0)) return 0.0;
    // sum held the excesses; now turn each into the volume that levels its edge alone.
    const double inv_ai = 1.0 / area[i];
    double levelling = 0.0;
    for (std::uint32_t k = begin; k < begin + degree; ++k) {
        if (q[k] > 0.0) {
            q[k] = q[k] / (inv_ai + 1.0 / area[target[k]]);
            levelling += q[k];
        }
    }
    double scale = std::min(share, 1.0);  // the schedule's levelling share, at most whole
    const double cap = p.damping * largest * area[i];
    if (scale * levelling > cap) scale = cap / levelling;
    const double available = area[i] * (hi - bedrock[i]);
    if (scale * levelling > available) scale = std::max(available, 0.0) / levelling;
    double sent = 0.0;
    for (std::uint32_t k = begin; k < begin + degree; ++k) {
        if (q[k] > 0.0) {
            q[k] *= scale;
            sent += q[k];
        }
    }
    return sent;
}

}  // namespace sandtin::test
