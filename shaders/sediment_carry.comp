#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 3 at one vertex: the suspended sand moves with the water at the sending vertex's
// concentration, scaled by what it holds. A vertex loses what it sends along its pipes and
// gains what its neighbours send it, each volume computed identically at both ends (from the
// sender's outflow, suspension, water and scale), so what leaves one vertex enters the
// other. Writes the other half of held and kind.
#include "sediment_common.glsl"

// m³ of suspension `from` sends along an outflow of `out_flux` m³/s this step.
float sent(uint from, float out_flux) {
    uint cur = pc.half_;
    precise float water_there = depth[from] * area[from];
    if (!(out_flux > 0.0) || !(water_there > 0.0)) return 0.0;
    precise float moved = out_flux * pc.dt * held[held_at(cur, from)] / water_there * scale[from];
    return moved;
}

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    uint cur = pc.half_;
    uint next = 1u - cur;
    float hv = held[held_at(cur, v)];
    float kinds_change[MAX_KINDS];
    for (uint k = 0u; k < pc.kinds; ++k)
        kinds_change[k] = 0.0;
    precise float change = 0.0;
    if (area[v] > 0.0) {
        uint begin = row_offset[v];
        uint end = begin + row_degree[v];
        uint now = pc.parity * pc.edge_capacity;
        for (uint k = begin; k < end; ++k) {
            uint w = target[k];
            if (!(area[w] > 0.0)) continue;
            float away = sent(v, q[now + k]);
            if (away > 0.0) {
                change -= away;
                float share = away / hv;
                for (uint j = 0u; j < pc.kinds; ++j)
                    kinds_change[j] -= share * kind[kind_at(cur, v, j)];
            }
            float towards = sent(w, q[now + reverse_slot[k]]);
            if (towards > 0.0) {
                change += towards;
                float share = towards / held[held_at(cur, w)];
                for (uint j = 0u; j < pc.kinds; ++j)
                    kinds_change[j] += share * kind[kind_at(cur, w, j)];
            }
        }
    }
    held[held_at(next, v)] = max(0.0, hv + change);
    for (uint j = 0u; j < pc.kinds; ++j)
        kind[kind_at(next, v, j)] = max(0.0, kind[kind_at(cur, v, j)] + kinds_change[j]);
}
