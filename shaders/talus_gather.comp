#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 2 of a Jacobi iteration: every receiver gathers, in its row order, what its source
// neighbours sent (no atomics: q of the reverse slot), and moves its texture-slide offset with
// the net transport (texture sliding after Onoue & Nishita, dT = -gamma Q E with E the uphill
// direction, i.e. the offset moves downhill with the material; wrapped to [0, 1)).
#include "talus_common.glsl"

void main() {
    uint idx = thread_index();
    if (idx >= ctl[C_RECEIVERS]) return;
    uint v = lists[R_RECEIVERS * pc.capacity + idx];
    bool is_source = vs[v].source == pc.iter;
    float delta = is_source ? -outflow[v] : 0.0;
    vec2 transport = vec2(0.0);
    uint begin = row_offset[v];
    vec2 pv = pc.slide_gain > 0.0 ? position[v] : vec2(0.0);
    for (uint k = begin; k < begin + row_degree[v]; ++k) {
        uint w = target[k];
        float net = is_source ? q[k] : 0.0;  // out along v -> w
        if (vs[w].source == pc.iter) {
            float qin = q[reverse_slot[k]];
            delta += qin;
            net -= qin;
        }
        // Texture sliding only when enabled (a uniform branch: no position reads otherwise).
        if (pc.slide_gain > 0.0 && net != 0.0)
            transport += net * (position[w] - pv) / edge_length[k];
    }
    // Compensated update: the residual (m³) carries whatever the float height could not take,
    // including the error of the division (SPIR-V division is not correctly rounded), so
    // rounding does not accumulate into a volume drift. nh - h is exact (Fast2Sum) whenever
    // |d| <= |h|, which holds for all but the first grains landing on bare ground.
    // `precise` forbids the compiler's algebraic shortcuts ((h + x) - h -> x) that would
    // silently cancel the compensation.
    float h = height[v];
    float a = area[v];
    precise float total = delta + vs[v].residual;
    precise float nh = h + total / a;
    // A source that sent all its sand lands on the bedrock, never below it by rounding (the
    // residual keeps the difference, so no volume is lost). Written back, a height below the
    // bedrock would carry the TIN's bedrock down with it.
    if (total < 0.0 && nh < bedrock[v]) nh = min(h, bedrock[v]);
    precise float applied = nh - h;
    precise float residual = total - applied * a;
    vs[v].residual = residual;
    if (nh != h) {
        height[v] = nh;
        vs[v].changed = pc.iter;
        append(R_CHANGED, C_CHANGED, v);
        // v is this invocation's own vertex: no atomic needed.
        if (vs[v].touched == 0u) append(R_TOUCHED, C_TOUCHED, v);
        vs[v].touched = TOUCHED_LISTED | TOUCHED_SURFACE;
    }
    if (pc.slide_gain > 0.0 && (transport.x != 0.0 || transport.y != 0.0)) {
        slide[v] = fract(slide[v] + pc.slide_gain * transport / area[v]);
        if (vs[v].touched == 0u) append(R_TOUCHED, C_TOUCHED, v);
        vs[v].touched = TOUCHED_LISTED | TOUCHED_SURFACE;
    }
}
