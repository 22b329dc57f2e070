// Sand carried by the water on the GPU: the buffers shared by its kernels. The law is
// engine/water/sediment_transport.hpp's (its double CPU twin), after each water step
// (gpu_water.hpp's WaterStepHook), vertex-parallel:
//  - sediment_capacity: each vertex's flow speed and steepest bed slope from its pipes, and
//    its transport capacity;
//  - sediment_exchange: each vertex picks sand up from its bed (of the material on top) or
//    drops some towards the capacity, and works out the share of its suspension it can send;
//  - sediment_carry: each vertex loses what it sends along its pipes and gains what its
//    neighbours send it (the same float, read through the reverse slots), material by
//    material.
// The bed's height is float: what a height cannot take of a change stays in the vertex's
// bed residual (m³), so sum(area height + residual) + suspended is kept to rounding.
#ifndef SANDTIN_SEDIMENT_COMMON_GLSL
#define SANDTIN_SEDIMENT_COMMON_GLSL

#include "common.glsl"

#define MAX_KINDS 8

layout(std430, binding = 0) readonly buffer Positions { vec2 position[]; };
layout(std430, binding = 1) buffer Heights { float height[]; };  // the bed (m, mirror origin)
layout(std430, binding = 2) readonly buffer Bedrocks { float bedrock[]; };
layout(std430, binding = 3) readonly buffer Areas { float area[]; };
layout(std430, binding = 4) readonly buffer Depths { float depth[]; };
layout(std430, binding = 5) readonly buffer RowOffsets { uint row_offset[]; };
layout(std430, binding = 6) readonly buffer RowDegrees { uint row_degree[]; };
layout(std430, binding = 7) readonly buffer Targets { uint target[]; };
layout(std430, binding = 8) readonly buffer Reverses { uint reverse_slot[]; };
layout(std430, binding = 9) readonly buffer Lengths { float edge_length[]; };
layout(std430, binding = 10) readonly buffer Flux { float q[]; };  // the water's outflows
layout(std430, binding = 11) buffer Capacity { float capacity[]; };  // m³ per vertex
// Two halves of stride (held) and of stride x kinds (kind): the current one and the one
// sediment_carry writes.
layout(std430, binding = 12) buffer Held { float held[]; };  // m³ suspended
layout(std430, binding = 13) buffer Kinds { float kind[]; };  // m³ suspended per material
layout(std430, binding = 14) buffer Dropped { float dropped[]; };  // m³ dropped per material
layout(std430, binding = 15) buffer Scale { float scale[]; };  // share of the sending kept
layout(std430, binding = 16) readonly buffer BedKinds { uint bed_kind[]; };
layout(std430, binding = 17) buffer BedResidual { float bed_residual[]; };  // m³

layout(push_constant) uniform Push {
    uint vertex_count;
    uint edge_capacity;
    uint parity;  // the half of q the water's step wrote
    uint half_;   // the current half of held and kind
    uint kinds;   // materials in the palette, <= MAX_KINDS
    uint stride;  // vertices per half of held and kind (the buffers' capacity)
    float dt;
    float capacity_k;   // K_c
    float pick_up;      // K_s (1/s)
    float drop_rate;    // K_d (1/s)
    float least_slope;  // s_min
    float max_concentration;  // c_max
} pc;

// height[v] += volume / area, what the float cannot take kept in bed_residual[v].
void move_bed(uint v, float volume, float av) {
    precise float h = height[v];
    precise float nh = h + volume / av;
    precise float applied = (nh - h) * av;
    bed_residual[v] += volume - applied;
    height[v] = nh;
}

uint held_at(uint half_index, uint v) {
    return half_index * pc.stride + v;
}
uint kind_at(uint half_index, uint v, uint k) {
    return (half_index * pc.stride + v) * pc.kinds + k;
}

#endif
