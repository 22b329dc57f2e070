// Talus relaxation on the GPU: the buffers and control block shared by its kernels. The
// arithmetic transcribes engine/physics/talus_kernel.hpp and face_kernel.hpp (CPU Jacobi
// schedule) in float.
#ifndef SANDTIN_TALUS_COMMON_GLSL
#define SANDTIN_TALUS_COMMON_GLSL

#include "common.glsl"

// Control block (uint words). Lists live in `lists` at region * capacity.
#define C_ACTIVE 0      // entries in the current active list
#define C_NEXT 1        // entries appended to the next active list
#define C_RECEIVERS 2
#define C_CHANGED 3
#define C_SPLIT 4
#define C_PARITY 5      // which half of lists[0..2 capacity) is current
#define C_TOUCHED 6
#define C_PROCESSED_LO 7
#define C_PROCESSED_HI 8
#define C_CHANGED_TOTAL_LO 9
#define C_CHANGED_TOTAL_HI 10
#define C_WORK_ITER_LO 11   // 64-bit count of iterations that had work (TalusSolver::iteration())
#define C_WORK_ITER_HI 12
#define C_ARGS_ACTIVE 16    // 3 words: indirect dispatch of the active list
#define C_ARGS_RECEIVERS 20
#define C_ARGS_CHANGED 24

#define R_RECEIVERS 2u
#define R_CHANGED 3u
#define R_SPLIT 4u
#define R_TOUCHED 5u

struct VertexState {
    uint source;    // iteration stamp: computed an outflow
    uint receiver;  // iteration stamp: in the receiver list
    uint changed;   // iteration stamp: height changed
    uint split;     // split_batch stamp: in the split list
    uint quiet;     // still iterations while active
    uint in_list;   // 1 while in the active list
    uint touched;   // TOUCHED_* bits: in the touched list, and why (reset at read-back)
    float residual; // m³ the last height update could not represent (compensated sum)
    float moved;    // m³ it sent since the last read-back (the volume_moved of a step)
};

// VertexState::touched: listed for the next read-back; its height or slide changed (else it
// is listed only for the volume it sent).
#define TOUCHED_LISTED 1u
#define TOUCHED_SURFACE 2u

// One read-back entry (gpu_relaxation.hpp TouchedVertex).
struct PackedVertex {
    uint id;
    float height;
    float slide_x;
    float slide_y;
    float moved;
    uint touched;
};

layout(std430, binding = 0) buffer Control { uint ctl[]; };
layout(std430, binding = 1) buffer Heights { float height[]; };
layout(std430, binding = 2) readonly buffer Areas { float area[]; };
layout(std430, binding = 3) readonly buffer Bedrock { float bedrock[]; };
layout(std430, binding = 4) readonly buffer TanAlpha { float tan_alpha[]; };
layout(std430, binding = 5) readonly buffer RowOffset { uint row_offset[]; };
layout(std430, binding = 6) readonly buffer RowDegree { uint row_degree[]; };
layout(std430, binding = 7) readonly buffer Target { uint target[]; };
layout(std430, binding = 8) readonly buffer Reverse { uint reverse_slot[]; };
layout(std430, binding = 9) readonly buffer Length { float edge_length[]; };
layout(std430, binding = 10) readonly buffer Longest { float longest[]; };
layout(std430, binding = 11) buffer Flow { float q[]; };
layout(std430, binding = 12) buffer Out { float outflow[]; };
layout(std430, binding = 13) buffer State { VertexState vs[]; };
layout(std430, binding = 14) buffer Lists { uint lists[]; };
layout(std430, binding = 15) readonly buffer Position { vec2 position[]; };
layout(std430, binding = 16) buffer Slide { vec2 slide[]; };
layout(std430, binding = 17) buffer Packed { PackedVertex packed_out[]; };

layout(push_constant) uniform Push {
    uint iter;          // iteration stamp (>= 1), unique per iteration
    uint capacity;      // vertex capacity: size of each list region
    uint mode;          // kernel-specific
    uint quiet_limit;   // K
    float damping;
    float rest_tolerance;
    float r_limit;      // relocation radius (1 + 1e-9 slack applied on the host); 1e30 = none
    float slide_gain;   // gamma: texture units per metre of transported height; 0 = off
    uint seed_lo;       // TalusSettings::seed
    uint seed_hi;
    float randomness;   // TalusSettings::randomness; 0 = no jitter
    float settle_margin;  // TalusParameters::settle_margin: flowing edges level to (1 - m) r tan
    uint split_batch;   // stamp of the split requests since the host last took them (>= 1)
} pc;

void set_args(uint word, uint threads) {
    uint groups = (threads + LOCAL_SIZE - 1) / LOCAL_SIZE;
    uint x = min(groups, 65535u);
    ctl[word] = x;
    ctl[word + 1] = x == 0u ? 0u : (groups + x - 1u) / x;
    ctl[word + 2] = 1u;
}

void append(uint region, uint counter, uint v) {
    uint slot = atomicAdd(ctl[counter], 1u);
    if (slot < pc.capacity) lists[region * pc.capacity + slot] = v;
}

#endif
