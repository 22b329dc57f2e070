#pragma once
// Independent checks of sand-physics results, computed from the TIN alone (never from the
// solver's own bookkeeping): steepest edge, the pile's apex and toe, and a point pour; and the
// rough terrain and the id sorting that several physics tests share.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "physics/sand_physics.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

/// A random field with slopes far above repose: bumps of 5 cm, a few centimetres across
/// (heights in m, for x, y in metres).
inline double rough_sand(Vec2 p) {
    return 0.05 * (std::sin(37.0 * p.x) * std::cos(29.0 * p.y) + std::sin(91.0 * p.x + 3.0 * p.y));
}

/// The ids in increasing order, to compare lists that agree as sets.
inline std::vector<std::uint32_t> sorted_ids(std::vector<std::uint32_t> ids) {
    std::sort(ids.begin(), ids.end());
    return ids;
}

/// Largest (h(v) - h(w)) / (r_vw tan(alpha)) over the TIN's edges v-w that `skip(v, w)`
/// does not exclude (1 = exactly at repose), with the heights h(id) given (a GPU's, say).
template <class Height, class Skip>
double steepest_edge_ratio(const Tin& tin, double tan_alpha, Height h, Skip skip) {
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> ring;
    double worst = 0.0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        tin.neighbours(VertexId{v}, ring);
        for (VertexId w : ring) {
            if (skip(v, w.value)) continue;
            const double r = distance(va.position[v], va.position[w.value]);
            worst = std::max(worst, (h(v) - h(w.value)) / (r * tan_alpha));
        }
    }
    return worst;
}

/// The same over every edge, with the TIN's heights.
inline double steepest_edge_ratio(const Tin& tin, double tan_alpha) {
    const VertexArrays& va = tin.vertices();
    return steepest_edge_ratio(
        tin, tan_alpha, [&](std::uint32_t v) { return va.height[v]; },
        [](std::uint32_t, std::uint32_t) { return false; });
}

struct PileShape {
    double apex = 0.0;          ///< highest vertex (m)
    double toe_radius = 0.0;    ///< mean distance from the centre at which the surface drops to
                                ///< `toe_level` along 32 rays (m)
    double toe_nearest = 0.0;   ///< the smallest of those distances (m)
    double toe_farthest = 0.0;  ///< the largest (m)
    double toe_spread() const { return toe_farthest - toe_nearest; }
};

/// The pile around `centre`: apex height, and where the surface falls to `toe_level` along
/// rays (from the exact piecewise-linear section of the TIN), spread evenly over the angles
/// [from, to] (radians; a pile against a wall or in a corner has rays only into the domain).
inline PileShape measure_pile(const Tin& tin, Vec2 centre, double reach, double toe_level,
                              double from = 0.0, double to = 2.0 * std::numbers::pi) {
    PileShape s;
    const VertexArrays& va = tin.vertices();
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (va.alive[v]) s.apex = std::max(s.apex, va.height[v]);
    }
    double lo = 1e300, hi = 0.0, sum = 0.0;
    constexpr int kRays = 32;
    const Rect domain = tin.domain();
    for (int k = 0; k < kRays; ++k) {
        const double a = from + (to - from) * (k + 0.5) / kRays;
        const Vec2 dir{std::cos(a), std::sin(a)};
        // Each ray ends at the domain's border if it gets there first: Tin::section clamps its
        // ends into the domain, which would bend the ray and stretch its parameter.
        double length = reach;
        if (dir.x > 0.0) length = std::min(length, (domain.max.x - centre.x) / dir.x);
        if (dir.x < 0.0) length = std::min(length, (domain.min.x - centre.x) / dir.x);
        if (dir.y > 0.0) length = std::min(length, (domain.max.y - centre.y) / dir.y);
        if (dir.y < 0.0) length = std::min(length, (domain.min.y - centre.y) / dir.y);
        const auto sec = tin.section(centre, centre + dir * length);
        double r = length;
        for (std::size_t i = 1; i < sec.size(); ++i) {
            const auto [t0, z0] = sec[i - 1];
            const auto [t1, z1] = sec[i];
            if (z0 > toe_level && z1 <= toe_level) {
                r = length * (t0 + (t1 - t0) * (z0 - toe_level) / (z0 - z1));
                break;
            }
        }
        lo = std::min(lo, r);
        hi = std::max(hi, r);
        sum += r;
    }
    s.toe_radius = sum / kRays;
    s.toe_nearest = lo;
    s.toe_farthest = hi;
    return s;
}

/// Pours `volume` m³ onto the vertex at `at` (inserted if needed): first the edges around it
/// are split at r_S so the pour has a star of radius r_S, then the vertex rises by V / A.
inline VertexId pour_at_point(Tin& tin, SandPhysics& physics, Vec2 at, double volume) {
    const VertexId v = tin.insert_point_on_surface(at);
    const VertexId one[] = {v};
    physics.refine_around(one);
    tin.set_height(v, tin.height(v) + volume / tin.vertices().lumped_area[v.value]);
    return v;
}

}  // namespace sandtin::test
