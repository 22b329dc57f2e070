#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 1 of a Jacobi relaxation iteration: the outflow of every active vertex along each of
// its directed edges, from the old heights (engine/physics/talus_kernel.hpp, in float). A
// vertex that sends anything enters the receiver list with all its neighbours.
#include "talus_outflow_common.glsl"

void main() {
    uint idx = thread_index();
    if (idx >= ctl[C_ACTIVE]) return;
    uint i = lists[ctl[C_PARITY] * pc.capacity + idx];
    uint begin = row_offset[i];
    uint degree = row_degree[i];
    vs[i].source = pc.iter;
    float sent = 0.0;
    if (degree > 0u) {
        float hi = height[i];
        float tan_a = tan_alpha[i];
        float inv_ai = 1.0 / area[i];
        // The CPU uses 64 double ulps; in float, 4 ulps of the height is the rounding noise
        // below which two nearly coincident vertices would trade the last bit forever.
        float noise_floor = 4.0 * kFloatEpsilon * abs(hi);
        // Pass 1: excesses and levelling volumes, nothing stored. Pass 2 recomputes them with
        // the same float operations (so the same values) and writes q once: half the memory
        // traffic of storing and re-reading q like the CPU does.
        float largest = 0.0;
        float sum = 0.0;
        float levelling = 0.0;
        for (uint k = begin; k < begin + degree; ++k) {
            float r = edge_length[k];
            float slope = r * tan_a;
            uint t = target[k];
            float e = (hi - height[t]) - slope;
            if (!(e > pc.rest_tolerance * slope) || !(e > noise_floor)) continue;
            if (r > pc.r_limit) {
                request_split(i);
                continue;
            }
            if (longest[t] > pc.r_limit) {
                request_split(t);
                continue;
            }
            // A degenerate receiver takes nothing (kDegenerateAreaRatio, talus_kernel.hpp).
            if (area[t] < kDegenerateAreaRatio * area[i]) continue;
            // Flowing sand settles a margin below the angle it started at (== e when m = 0).
            float excess = e + pc.settle_margin * slope;
            sum += excess;
            largest = max(largest, excess);
            levelling += excess / (inv_ai + 1.0 / area[t]);
        }
        float scale = 0.0;
        if (sum > 0.0) scale = row_scale(i, hi, largest, levelling);
        // Pass 2: every slot of the row is written (receivers read q of every source's row).
        for (uint k = begin; k < begin + degree; ++k) {
            float v = 0.0;
            if (scale > 0.0) {
                float r = edge_length[k];
                float slope = r * tan_a;
                uint t = target[k];
                float e = (hi - height[t]) - slope;
                if (e > pc.rest_tolerance * slope && e > noise_floor && !(r > pc.r_limit) &&
                    !(longest[t] > pc.r_limit) && !(area[t] < kDegenerateAreaRatio * area[i])) {
                    v = ((e + pc.settle_margin * slope) / (inv_ai + 1.0 / area[t])) * scale;
                }
            }
            q[k] = v;
            sent += v;
        }
    }
    finish_outflow(i, begin, degree, sent);
}
