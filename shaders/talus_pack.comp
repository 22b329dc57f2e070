#version 450
#extension GL_GOOGLE_include_directive : require
// Read-back: packs (id, height, slide) of every touched vertex for one small host copy, and
// clears its touched flag.
#include "talus_common.glsl"

void main() {
    uint idx = thread_index();
    if (idx >= min(ctl[C_TOUCHED], pc.capacity)) return;
    uint v = lists[R_TOUCHED * pc.capacity + idx];
    packed_out[idx] = uvec4(v, floatBitsToUint(height[v]), floatBitsToUint(slide[v].x),
                            floatBitsToUint(slide[v].y));
    vs[v].touched = 0u;
}
