#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 3 of a pipe step at one vertex: it loses its outflows and gains its neighbours'
// (read through the reverse slots, so each volume leaves one vertex and enters the other as
// the same float), and loses what went over an open border. The sum is compensated
// (Neumaier) and what the float depth cannot take stays in the vertex's residual, so rounding
// does not accumulate into a volume drift. `precise` forbids the algebraic shortcuts that
// would cancel the compensation.
#include "water_common.glsl"

// Neumaier's step: sum += x, with the rounding error of that addition kept in compensation.
void add(inout precise float sum, inout precise float compensation, float x) {
    precise float t = sum + x;
    if (abs(sum) >= abs(x)) {
        compensation += (sum - t) + x;
    } else {
        compensation += (x - t) + sum;
    }
    sum = t;
}

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float av = area[v];
    if (!(av > 0.0)) return;  // holds no water: no pipe reaches it
    uint begin = row_offset[v];
    uint end = begin + row_degree[v];
    uint now = pc.parity * pc.edge_capacity;
    precise float sum = residual[v];
    precise float compensation = 0.0;
    for (uint k = begin; k < end; ++k) {
        precise float sent = q[now + k] * pc.dt;
        precise float received = q[now + reverse_slot[k]] * pc.dt;
        add(sum, compensation, -sent);
        add(sum, compensation, received);
    }
    float h = depth[v];
    precise float over = overfall(v, h) * keep[v] * pc.dt;
    if (over > 0.0) {
        add(sum, compensation, -over);
        left[v] += over;
    }
    precise float total = sum + compensation;
    if (total == 0.0 && residual[v] == 0.0) return;
    precise float nh = h + total / av;
    // The scale K keeps a vertex from sending more than it holds, up to rounding; the
    // residual keeps that rounding (negative), so no depth is ever below 0 and no volume lost.
    if (nh < 0.0) nh = 0.0;
    precise float applied = nh - h;
    precise float rest = fma(-applied, av, sum) + compensation;
    residual[v] = rest;
    depth[v] = nh;
}
