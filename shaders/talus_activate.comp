#version 450
#extension GL_GOOGLE_include_directive : require
// Activation (ActiveSet::activate): every changed vertex and its neighbours get a fresh quiet
// count and join the next active list unless already in it. mode 1 (seeding from the host
// list in the changed region, the vertices an outside edit changed): the same, into the
// current list. The neighbours matter: lowering a vertex steepens the edges from the higher
// neighbours, and only they can send sand down them.
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
    bool seeding = pc.mode == 1u;
    uint into = seeding ? ctl[C_PARITY] : 1u - ctl[C_PARITY];
    uint counter = seeding ? C_ACTIVE : C_NEXT;
    activate(v, into, counter);
    uint begin = row_offset[v];
    for (uint k = begin; k < begin + row_degree[v]; ++k) activate(target[k], into, counter);
}
