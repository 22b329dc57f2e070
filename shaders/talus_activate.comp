#version 450
#extension GL_GOOGLE_include_directive : require
// Activation (ActiveSet::activate): every changed vertex and its neighbours get a fresh quiet
// count and join the next active list unless already in it. mode 1 (seeding from the host
// list in the changed region): the vertices themselves only, into the current list.
#include "talus_common.glsl"

void activate(uint u, uint list_half, uint counter) {
    vs[u].quiet = 0u;
    if (vs[u].in_list == 1u) return;  // already listed (plain read spares most atomics)
    if (atomicExchange(vs[u].in_list, 1u) == 0u) append(list_half, counter, u);
}

void main() {
    uint idx = thread_index();
    if (idx >= ctl[C_CHANGED]) return;
    uint v = lists[R_CHANGED * pc.capacity + idx];
    if (pc.mode == 1u) {
        activate(v, ctl[C_PARITY], C_ACTIVE);
        return;
    }
    uint next_half = 1u - ctl[C_PARITY];
    activate(v, next_half, C_NEXT);
    uint begin = row_offset[v];
    for (uint k = begin; k < begin + row_degree[v]; ++k) activate(target[k], next_half, C_NEXT);
}
