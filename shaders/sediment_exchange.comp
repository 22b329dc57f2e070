#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 2 at one vertex: below its capacity it takes min(K_s (C - held) dt, the sand above
// its rock) from its bed, of the material on top (what was dropped there most, else the
// bed's own); above it, it drops K_d (held - C) dt, each material in proportion. The bed's
// height follows, its float rounding kept in the bed residual. Then the share of its
// suspension it can send along its pipes this step: what the flow would carry at its
// concentration, scaled down to what it holds.
#include "sediment_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float av = area[v];
    if (!(av > 0.0)) return;
    uint cur = pc.half_;
    float c = capacity[v];
    float h = held[held_at(cur, v)];
    if (h < c) {
        // The rock is never eroded: the sand above it, with the residual's share.
        precise float sand = max(0.0, (height[v] - bedrock[v]) * av + bed_residual[v]);
        float taken = min(pc.pick_up * (c - h) * pc.dt, sand);
        if (taken > 0.0) {
            uint top = bed_kind[v];
            for (uint k = 0u; k < pc.kinds; ++k)
                if (dropped[v * pc.kinds + k] > dropped[v * pc.kinds + top]) top = k;
            held[held_at(cur, v)] = h + taken;
            kind[kind_at(cur, v, top)] += taken;
            move_bed(v, -taken, av);
            if (height[v] < bedrock[v]) {
                // Rounding took the float bed below the rock: the rock is the floor, the
                // difference stays in the residual.
                bed_residual[v] -= (bedrock[v] - height[v]) * av;
                height[v] = bedrock[v];
            }
        }
    } else if (h > 0.0) {
        float fall = min(pc.drop_rate * (h - c) * pc.dt, h);
        float share = fall / h;
        for (uint k = 0u; k < pc.kinds; ++k) {
            float part = share * kind[kind_at(cur, v, k)];
            dropped[v * pc.kinds + k] += part;
            kind[kind_at(cur, v, k)] = max(0.0, kind[kind_at(cur, v, k)] - part);
        }
        held[held_at(cur, v)] = h - fall;
        move_bed(v, fall, av);
    }
    // What the flow would carry away at this vertex's concentration, and the scale that keeps
    // it within what the vertex holds.
    h = held[held_at(cur, v)];
    float water_here = depth[v] * av;
    float out_volume = 0.0;
    if (water_here > 0.0 && h > 0.0) {
        uint begin = row_offset[v];
        uint end = begin + row_degree[v];
        uint now = pc.parity * pc.edge_capacity;
        for (uint k = begin; k < end; ++k)
            if (area[target[k]] > 0.0) out_volume += q[now + k] * pc.dt * h / water_here;
    }
    scale[v] = out_volume > h ? h / out_volume : 1.0;
}
