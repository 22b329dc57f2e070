// Phase 1 of a Jacobi iteration, shared by the edge rule's kernel (talus_outflow.comp) and the
// face rule's (talus_face_outflow.comp): marking, split requests, the jitter and the row's
// scale (engine/physics/talus_kernel.hpp outflow_scale, in float).
#ifndef SANDTIN_TALUS_OUTFLOW_COMMON_GLSL
#define SANDTIN_TALUS_OUTFLOW_COMMON_GLSL

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

// The factor the row's levelling volumes (m³, summed in row order) are scaled by: the Jacobi
// schedule's levelling share (damping) and jitter, at most 1 (no edge carries more than levels
// it), the cap on i's drop (damping times the largest excess, m), the sand above the bedrock.
float row_scale(uint i, float hi, float largest, float levelling) {
    float scale = pc.damping;
    if (pc.randomness > 0.0) {
        uvec2 it = uvec2(ctl[C_WORK_ITER_LO], ctl[C_WORK_ITER_HI]);
        scale *= 1.0 + pc.randomness * signed_unit_hash(uvec2(pc.seed_lo, pc.seed_hi), i, it);
    }
    scale = min(scale, 1.0);
    float cap = pc.damping * largest * area[i];
    if (scale * levelling > cap) scale = cap / levelling;
    float available = area[i] * (hi - bedrock[i]);
    if (scale * levelling > available) scale = max(available, 0.0) / levelling;
    return scale;
}

// The end of phase 1 for vertex i, which sent `sent` m³ along its row.
void finish_outflow(uint i, uint begin, uint degree, float sent) {
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

#endif
