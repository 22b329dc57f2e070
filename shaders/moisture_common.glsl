// Moisture in the sand on the GPU: the buffers and control words shared by its kernels. The
// scheme is engine/water/moisture_diffusion.hpp's (its double CPU twin), taken
// vertex-parallel: each vertex gathers the exchanges along its CSR row, each computed at both
// ends with negated inputs (`precise`, cotangent weights symmetric in the edge's ends), so
// what leaves one end is what enters the other, to the rounding of each vertex's sum.
#ifndef SANDTIN_MOISTURE_COMMON_GLSL
#define SANDTIN_MOISTURE_COMMON_GLSL

#include "common.glsl"

// Control words (gpu_moisture.cpp, must match).
#define C_WET 0       // vertices with moisture > 0 after the run
#define C_WETTEST 1   // float bits: the largest moisture
#define C_SLOWED 2    // vertex-sub-steps whose exchanges were slowed

layout(std430, binding = 0) buffer Control { uint ctl[]; };
layout(std430, binding = 1) readonly buffer Positions { vec2 position[]; };
layout(std430, binding = 2) readonly buffer Areas { float area[]; };
layout(std430, binding = 3) buffer Moisture { float moisture[]; };  // the mirror's
layout(std430, binding = 4) buffer Scratch { float scratch[]; };    // the other half
layout(std430, binding = 5) readonly buffer RowOffsets { uint row_offset[]; };
layout(std430, binding = 6) readonly buffer RowDegrees { uint row_degree[]; };
layout(std430, binding = 7) readonly buffer Targets { uint target[]; };
layout(std430, binding = 8) readonly buffer Across { float across[]; };
// Per vertex: the sum of its edges' cotangent weights (edges to vertices of area > 0), and
// A / that sum (s x m²/s: the vertex's stability bound is 0.5 ratio / D), +inf without edges.
layout(std430, binding = 9) buffer WeightSums { float weight_sum[]; };
layout(std430, binding = 10) buffer Ratios { float ratio[]; };
layout(std430, binding = 11) readonly buffer Depths { float depth[]; };  // water (m)

layout(push_constant) uniform Push {
    uint vertex_count;
    uint parity;     // 0: moisture -> scratch, 1: scratch -> moisture
    uint drying;     // 1: moisture below the threshold is dry (0) at the end of a run
    uint pad;
    float d_dt;       // D dt (m²): diffusivity times the sub-step
    float decay;      // 2^(-dt / T) over the sub-step (1: no drying)
    float threshold;  // kNegligibleMoisture
    float wet_depth;  // moisture_wet: water at least this deep (m) wets the sand under it ...
    float wet_moisture;  // ... to this saturation
} pc;

#include "cotangent.glsl"

float moisture_in(uint v) {
    return pc.parity == 0u ? moisture[v] : scratch[v];
}

#endif
