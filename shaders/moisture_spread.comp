#version 450
#extension GL_GOOGLE_include_directive : require
// One sub-step of spreading and drying at one vertex (moisture_diffusion.hpp):
//   m_i += (1 / A_i) sum_j D dt s_ij w_ij (m_j - m_i),  then m_i *= 2^(-dt / T),
// with s_ij = min(s_i, s_j) and s_i = min(1, 0.5 A_i / (D dt sum_j w_ij)) (a vertex whose own
// bound is below the sub-step has its exchanges slowed, so it keeps at least half its
// weight). An edge whose ends are both below the threshold exchanges nothing.
#include "moisture_common.glsl"

float slowing(uint v) {
    float load = pc.d_dt * weight_sum[v];
    return load > 0.5 * area[v] ? 0.5 * area[v] / load : 1.0;
}

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float mv = moisture_in(v);
    float av = area[v];
    precise float flow = 0.0;
    if (av > 0.0 && pc.d_dt > 0.0) {
        uint begin = row_offset[v];
        uint end = begin + row_degree[v];
        float sv = slowing(v);
        if (sv < 1.0) atomicAdd(ctl[C_SLOWED], 1u);
        for (uint k = begin; k < end; ++k) {
            uint w = target[k];
            float mw = moisture_in(w);
            if (max(mv, mw) < pc.threshold || !(area[w] > 0.0)) continue;
            float c = conductance(v, k, begin, end);
            if (!(c > 0.0)) continue;
            precise float exchange = pc.d_dt * c * min(sv, slowing(w)) * (mw - mv);
            flow += exchange;
        }
    }
    precise float m = (mv + flow / max(av, 1e-30)) * pc.decay;
    if (pc.parity == 0u)
        scratch[v] = m;
    else
        moisture[v] = m;
}
