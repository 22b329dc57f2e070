#version 450
#extension GL_GOOGLE_include_directive : require
// Read-back: packs (id, height, slide, volume sent, why listed) of every touched vertex for one
// small host copy, and clears its touched flags and its volume sent.
#include "talus_common.glsl"

void main() {
    uint idx = thread_index();
    if (idx >= min(ctl[C_TOUCHED], pc.capacity)) return;
    uint v = lists[R_TOUCHED * pc.capacity + idx];
    packed_out[idx] = PackedVertex(v, height[v], slide[v].x, slide[v].y, vs[v].moved,
                                   vs[v].touched);
    vs[v].touched = 0u;
    vs[v].moved = 0.0;
}
