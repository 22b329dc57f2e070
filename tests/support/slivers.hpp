#pragma once
// Vertical slivers: vertices with next to no area in the plane, which the relaxation's
// degenerate-receiver rule (kDegenerateAreaRatio, engine/physics/talus_kernel.hpp) lets take
// nothing; how to find them, and a terrain that has them.
//
// The terrain: three constrained chains a hair
// (1e-11 m) apart along y = 0.5, what overlapping rims of successive stamps once left behind
// (the TIN no longer makes them at its default snap distance; this scene turns snapping off).
// Every triangle around a vertex of the middle chain lies between two constraints that close,
// so it has no area in the plane. A plateau 0.1 m high stands on the far side, the floor at 0
// on the near side, and in between the chains a vertical cliff whose only way down leads
// through the middle chain (at 0.05 m).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "physics/talus_kernel.hpp"
#include "tin/tin.hpp"

namespace sandtin::test {

/// Whether one end of the edge v-w has under kDegenerateAreaRatio of the other's lumped area.
inline bool joins_sliver(const VertexArrays& va, std::uint32_t v, std::uint32_t w) {
    const double av = va.lumped_area[v], aw = va.lumped_area[w];
    return av < kDegenerateAreaRatio * aw || aw < kDegenerateAreaRatio * av;
}

/// Live vertices with under kDegenerateAreaRatio of some neighbour's lumped area.
inline std::size_t sliver_vertices(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    std::vector<VertexId> ring;
    std::size_t n = 0;
    for (std::uint32_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v]) continue;
        tin.neighbours(VertexId{v}, ring);
        n += std::any_of(ring.begin(), ring.end(),
                         [&](VertexId w) {
                             return va.lumped_area[v] <
                                    kDegenerateAreaRatio * va.lumped_area[w.value];
                         })
                 ? 1
                 : 0;
    }
    return n;
}

struct SliverScene {
    Tin tin;
    std::vector<VertexId> middle;  ///< the middle chain: vertices with next to no area
};

inline SliverScene vertical_sliver_scene(std::size_t points, std::uint64_t seed) {
    SliverScene s{Tin::random_points(Rect::from_size(1.0, 1.0), points, seed,
                                     [](Vec2 p) { return p.y > 0.5 ? 0.1 : 0.0; }),
                  {}};
    constexpr double kHair = 1e-11;
    // The TIN threads a constraint through a vertex within its snap distance, and puts a point
    // that close to a constrained edge on it, so at the default snap distance these chains
    // would be one. A TIN with a smaller snap distance (Tin::set_snap_distance) can still hold
    // such slivers, and the physics must cope with them: the scene snaps only what coincides.
    s.tin.set_snap_distance(0.0);
    // Chains of 7 points 0.1 m apart, staggered along x (points closer than the snap
    // distance would merge): the near one at the floor, the far one at the plateau, and the
    // middle one, shorter than both, half way up.
    auto chain = [&](double x0, int n, double y, double height) {
        std::vector<Vec2> ps;
        std::vector<double> hs;
        for (int k = 0; k < n; ++k) {
            ps.push_back({x0 + 0.1 * k, y});
            hs.push_back(height);
        }
        const std::vector<VertexId> ids = s.tin.insert_points(ps, hs);
        std::vector<std::array<VertexId, 2>> segments;
        for (std::size_t k = 0; k + 1 < ids.size(); ++k)
            segments.push_back({ids[k], ids[k + 1]});
        s.tin.insert_constraints(segments, 1);
        return ids;
    };
    chain(0.20, 7, 0.5, 0.0);
    chain(0.22, 7, 0.5 + 2.0 * kHair, 0.1);
    s.middle = chain(0.26, 6, 0.5 + kHair, 0.05);
    return s;
}

}  // namespace sandtin::test
