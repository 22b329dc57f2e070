#version 450
#extension GL_GOOGLE_include_directive : require
// Phases 1 and 2 of a pipe step at one vertex: each pipe of its row takes
// Q += dt g h_up (w/L) (eta_v - eta_w), damped by friction, from the signed flux the last
// step left (q[k] - q[reverse]); the vertex keeps its positive outflows, and scales them down
// together (K) when they would take more than it holds. Both ends compute one pipe with
// negated inputs, so one sees Q and the other -Q: only one of q[k], q[reverse] is non-zero.
#include "water_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    uint begin = row_offset[v];
    uint end = begin + row_degree[v];
    uint now = pc.parity * pc.edge_capacity;
    uint before = (1u - pc.parity) * pc.edge_capacity;
    float hv = depth[v];
    float av = area[v];
    precise float surface_v = height[v] + hv;
    precise float outflow = 0.0;
    for (uint k = begin; k < end; ++k) {
        uint w = target[k];
        float hw = depth[w];
        precise float flux = q[before + k] - q[before + reverse_slot[k]];
        // A dry pipe at rest stays so: most of a terrain, skipped without its cotangents.
        if (flux == 0.0 && hv == 0.0 && hw == 0.0) {
            q[now + k] = 0.0;
            continue;
        }
        float c = av > 0.0 && area[w] > 0.0 ? conductance(v, k, begin, end) : 0.0;
        precise float drop = surface_v - (height[w] + hw);
        float upwind = drop >= 0.0 ? hv : hw;
        flux = (flux + pc.dt * pc.gravity * upwind * c * drop) * pc.damping;
        float out_k = max(flux, 0.0);
        q[now + k] = out_k;
        outflow += out_k;
    }
    outflow += overfall(v, hv);
    precise float wanted = outflow * pc.dt;
    precise float held = hv * av;
    float scale = 1.0;
    if (wanted > held) {
        scale = held / wanted;
        for (uint k = begin; k < end; ++k)
            q[now + k] *= scale;
        atomicAdd(ctl[C_LIMITED], 1u);
    }
    keep[v] = scale;
}
