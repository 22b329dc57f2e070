#pragma once
// The water's view of a TIN (virtual_pipes.hpp): its vertices by id, its triangles, its lumped
// areas and its heights as the bed. Dead ids have no area and no faces, so no pipe reaches
// them.

#include <algorithm>

#include "tin/tin.hpp"
#include "water/virtual_pipes.hpp"

namespace sandtin {

WaterMesh water_mesh_of(const Tin& tin);

/// Gives `water` (built on water_mesh_of(tin)) the depths the terrain holds
/// (VertexArrays::water_depth), at rest: the water earlier operations or frames left.
template <class Water>
void load_water_depths(Water& water, const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    const std::size_t n = std::min(va.size(), water.vertex_count());
    for (std::size_t v = 0; v < n; ++v)
        if (va.alive[v] && va.water_depth[v] > 0.0) water.set_depth(v, va.water_depth[v]);
}

}  // namespace sandtin
