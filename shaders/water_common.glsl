// Water by virtual pipes on the GPU: the buffers and control words shared by its kernels.
// The scheme is engine/water/virtual_pipes.hpp's (its double CPU twin), taken vertex-parallel:
// each pipe's signed flux lives as two non-negative outflows, one per directed edge of the
// mirror's CSR rows (q[k] from the row's vertex to target[k]), so every kernel writes only
// its own vertex's entries and gathers its neighbours' through the reverse slot, no atomics.
#ifndef SANDTIN_WATER_COMMON_GLSL
#define SANDTIN_WATER_COMMON_GLSL

#include "common.glsl"

// Control words (gpu_water.cpp, must match).
#define C_LIMIT 0      // float bits: least stability limit over the vertices (s), +inf dry
#define C_WET 1        // vertices holding water
#define C_FLOWING 2    // vertices with an outflow
#define C_LIMITED 3    // outflows scaled to what a vertex held, summed over the steps
#define C_DEEPEST 4    // float bits: the deepest water (m)

layout(std430, binding = 0) buffer Control { uint ctl[]; };
layout(std430, binding = 1) readonly buffer Positions { vec2 position[]; };
layout(std430, binding = 2) readonly buffer Heights { float height[]; };
layout(std430, binding = 3) readonly buffer Areas { float area[]; };
layout(std430, binding = 4) buffer Depths { float depth[]; };
layout(std430, binding = 5) readonly buffer RowOffsets { uint row_offset[]; };
layout(std430, binding = 6) readonly buffer RowDegrees { uint row_degree[]; };
layout(std430, binding = 7) readonly buffer Targets { uint target[]; };
layout(std430, binding = 8) readonly buffer Reverses { uint reverse_slot[]; };
layout(std430, binding = 9) readonly buffer Across { float across[]; };
// Two halves of edge_capacity entries: the step writes one while its neighbours' previous
// outflows are read from the other (m³/s).
layout(std430, binding = 10) buffer Flux { float q[]; };
layout(std430, binding = 11) buffer Keep { float keep[]; };  // outflow scale K in [0, 1]
layout(std430, binding = 12) readonly buffer Borders { float border_width[]; };  // m
// m³ the float depth could not represent (compensated update): the volume is
// sum(area depth + residual), exact to the rounding of one vertex's sum per step.
layout(std430, binding = 13) buffer Residual { float residual[]; };
layout(std430, binding = 14) buffer Left { float left[]; };  // m³ out through the border

layout(push_constant) uniform Push {
    uint vertex_count;
    uint edge_capacity;
    uint parity;  // the half of q this step writes
    uint pad;
    float dt;       // s
    float gravity;  // m/s²
    float damping;  // 1 / (1 + dt friction)
    float pad2;
} pc;

#include "cotangent.glsl"

// Critical discharge of a free overfall over the border at v (m³/s): width h sqrt(g h).
float overfall(uint v, float h) {
    precise float discharge = border_width[v] * h * sqrt(pc.gravity * h);
    return discharge;
}

#endif
