#version 450
#extension GL_GOOGLE_include_directive : require
// After a run (the result in the mirror's moisture): with drying, moisture below the
// threshold is dry (0), as the CPU writes it; the scheme keeps m in [0, 1], the clamp only
// catches rounding at the ends. Counts the wet vertices and the wettest.
#include "moisture_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    if (!(area[v] > 0.0)) return;
    float m = clamp(moisture[v], 0.0, 1.0);
    if (pc.drying == 1u && m < pc.threshold) m = 0.0;
    moisture[v] = m;
    if (m > 0.0) {
        atomicAdd(ctl[C_WET], 1u);
        atomicMax(ctl[C_WETTEST], floatBitsToUint(m));
    }
}
