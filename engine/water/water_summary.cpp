#include "water/water_summary.hpp"

#include <algorithm>

#include "tin/vertex_arrays.hpp"

namespace sandtin {

WaterSummary measure_water(const Tin& tin) {
    const VertexArrays& va = tin.vertices();
    WaterSummary s;
    for (std::size_t v = 0; v < va.size(); ++v) {
        if (!va.alive[v] || va.water_depth[v] <= 0.0) continue;
        ++s.wet_vertices;
        s.volume += va.lumped_area[v] * va.water_depth[v];
        s.max_depth = std::max(s.max_depth, va.water_depth[v]);
    }
    return s;
}

}  // namespace sandtin
