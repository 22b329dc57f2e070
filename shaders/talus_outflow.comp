#version 450
#extension GL_GOOGLE_include_directive : require
// Phase 1 of a Jacobi relaxation iteration: the outflow of every active vertex along each of
// its directed edges, from the old heights (engine/physics/talus_kernel.hpp, in float). A
// vertex that sends anything enters the receiver list with all its neighbours.
#include "talus_common.glsl"

const float kFloatEpsilon = 1.1920929e-7;
// talus_kernel.hpp kDegenerateAreaRatio: an edge into a vertex with less lumped area than
// this fraction of the sender's carries nothing.
const float kDegenerateAreaRatio = 1e-6;

void mark_receiver(uint v) {
    // Plain read first: most neighbours are already marked, and a stamp, once set, stays for
    // the iteration; only the first marking needs the atomic.
    if (vs[v].receiver == pc.iter) return;
    if (atomicExchange(vs[v].receiver, pc.iter) != pc.iter) append(R_RECEIVERS, C_RECEIVERS, v);
}

void request_split(uint v) {
    // Once per batch: the host takes the list (and starts a new batch) only every few
    // iterations, and a vertex that stays blocked at a long edge asks again each iteration.
    if (atomicExchange(vs[v].split, pc.split_batch) != pc.split_batch) append(R_SPLIT, C_SPLIT, v);
}

// 64-bit arithmetic on (lo, hi) pairs, so no shaderInt64 is needed.
uvec2 mul64(uvec2 a, uvec2 b) {
    uint hi, lo;
    umulExtended(a.x, b.x, hi, lo);
    return uvec2(lo, hi + a.x * b.y + a.y * b.x);
}
uvec2 shr64(uvec2 a, uint s) {  // 0 < s < 32
    return uvec2((a.x >> s) | (a.y << (32u - s)), a.y >> s);
}

// physics/talus_kernel.hpp signed_unit_hash (splitmix64) in [-1, 1), to float precision.
float signed_unit_hash(uvec2 seed, uint vertex, uvec2 iteration) {
    uvec2 z = seed ^ mul64(uvec2(vertex, 0u), uvec2(0x7F4A7C15u, 0x9E3779B9u)) ^
              mul64(iteration, uvec2(0xD192ED03u, 0xD1B54A32u));
    z = mul64(z ^ shr64(z, 30u), uvec2(0x1CE4E5B9u, 0xBF58476Du));
    z = mul64(z ^ shr64(z, 27u), uvec2(0x133111EBu, 0x94D049BBu));
    z = z ^ shr64(z, 31u);
    z = shr64(z, 11u);  // 53 bits
    return float(z.y) * (2.0 / 2097152.0) + float(z.x) * (2.0 / 9007199254740992.0) - 1.0;
}

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
        if (sum > 0.0) {
            scale = pc.damping;
            if (pc.randomness > 0.0) {
                uvec2 it = uvec2(ctl[C_WORK_ITER_LO], ctl[C_WORK_ITER_HI]);
                scale *= 1.0 + pc.randomness *
                                   signed_unit_hash(uvec2(pc.seed_lo, pc.seed_hi), i, it);
            }
            float cap = pc.damping * largest * area[i];
            if (scale * levelling > cap) scale = cap / levelling;
            float available = area[i] * (hi - bedrock[i]);
            if (scale * levelling > available) scale = max(available, 0.0) / levelling;
        }
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
    outflow[i] = sent;
    if (sent > 0.0) {
        // Counted for the step's report at the next read-back, which also lists a vertex whose
        // height came out unchanged (what it sent came back). Only this invocation writes i's
        // state in this dispatch.
        vs[i].moved += sent;
        if (vs[i].touched == 0u) {
            vs[i].touched = TOUCHED_LISTED;
            append(R_TOUCHED, C_TOUCHED, i);
        }
        mark_receiver(i);
        for (uint k = begin; k < begin + degree; ++k) mark_receiver(target[k]);
    }
}
