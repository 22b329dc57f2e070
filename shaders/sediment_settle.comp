#version 450
#extension GL_GOOGLE_include_directive : require
// The end of a flow: every grain still suspended drops where it is (its materials counted
// as dropped there), raising the bed.
#include "sediment_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    uint cur = pc.half_;
    float h = held[held_at(cur, v)];
    float av = area[v];
    if (!(h > 0.0) || !(av > 0.0)) return;
    move_bed(v, h, av);
    for (uint k = 0u; k < pc.kinds; ++k) {
        dropped[v * pc.kinds + k] += kind[kind_at(cur, v, k)];
        kind[kind_at(cur, v, k)] = 0.0;
    }
    held[held_at(cur, v)] = 0.0;
}
