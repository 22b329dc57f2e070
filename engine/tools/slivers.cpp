#include "tools/slivers.hpp"

#include <algorithm>

namespace sandtin {

void equalise_slivers(Tin& tin, std::span<const VertexId> vertices, bool take_lower) {
    std::vector<VertexId> ring;
    const double snap = tin.snap_distance();
    const VertexArrays& va = tin.vertices();
    for (VertexId v : vertices) {
        if (!tin.is_alive(v)) continue;
        tin.neighbours(v, ring);
        for (VertexId w : ring) {
            if (distance(va.position[v.value], va.position[w.value]) > snap) continue;
            const double h = take_lower ? std::min(va.height[v.value], va.height[w.value])
                                        : std::max(va.height[v.value], va.height[w.value]);
            if (va.height[v.value] != h) tin.set_height(v, h);
            if (va.height[w.value] != h) tin.set_height(w, h);
        }
    }
}

}  // namespace sandtin
