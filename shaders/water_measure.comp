#version 450
#extension GL_GOOGLE_include_directive : require
// After a run: the stability limit of the next step (virtual_pipes.cpp stable_time_step: at
// each vertex sqrt(area / (g h sum(w/L))), h the deepest water at its pipes' ends), the
// vertices holding water and those still sending some, and the deepest water. A run that
// leaves none wet and none flowing lets the next run skip the GPU.
#include "water_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float av = area[v];
    if (!(av > 0.0)) return;
    uint begin = row_offset[v];
    uint end = begin + row_degree[v];
    uint now = pc.parity * pc.edge_capacity;
    float hv = depth[v];
    float deepest = 0.0;
    bool flowing = false;
    for (uint k = begin; k < end; ++k) {
        uint w = target[k];
        if (!(area[w] > 0.0)) continue;
        deepest = max(deepest, max(hv, depth[w]));
        flowing = flowing || q[now + k] != 0.0;
    }
    // Only a vertex beside water has a limit: dry land costs no cotangents.
    float conductances = 0.0;
    if (deepest > 0.0) {
        for (uint k = begin; k < end; ++k)
            if (area[target[k]] > 0.0) conductances += conductance(v, k, begin, end);
    }
    if (deepest > 0.0 && conductances > 0.0) {
        float limit = sqrt(av / (pc.gravity * deepest * conductances));
        atomicMin(ctl[C_LIMIT], floatBitsToUint(limit));  // positive floats order as uints
    }
    if (hv > 0.0) {
        atomicAdd(ctl[C_WET], 1u);
        atomicMax(ctl[C_DEEPEST], floatBitsToUint(hv));
    }
    if (flowing) atomicAdd(ctl[C_FLOWING], 1u);
}
