#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 1 at one vertex (sediment_transport.cpp): its discharge, half the sum of |Q| through
// its pipes (one of a pipe's two outflows is zero, so |Q| is their sum), its steepest bed
// slope along them, its speed discharge / (depth sqrt(area)) (water/virtual_pipes.hpp's
// pipe_flow_speed), and the capacity
//   C = min(K_c |u| max(slope, s_min) area, c_max depth area).
#include "sediment_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float av = area[v];
    if (!(av > 0.0)) {
        capacity[v] = 0.0;
        return;
    }
    uint begin = row_offset[v];
    uint end = begin + row_degree[v];
    uint now = pc.parity * pc.edge_capacity;
    float discharge = 0.0;
    float slope = 0.0;
    for (uint k = begin; k < end; ++k) {
        uint w = target[k];
        if (!(area[w] > 0.0)) continue;  // no pipe reaches a vertex without area
        discharge += 0.5 * (q[now + k] + q[now + reverse_slot[k]]);
        slope = max(slope, abs(height[v] - height[w]) / edge_length[k]);
    }
    float h = depth[v];
    float section = h > 0.0 ? h * sqrt(av) : 0.0;
    float speed = section > 0.0 ? discharge / section : 0.0;
    capacity[v] = min(pc.capacity_k * speed * max(slope, pc.least_slope) * av,
                      pc.max_concentration * h * av);
}
