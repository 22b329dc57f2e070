// Surface kernels (normals, map bake): bindings shared by their pipelines.
#ifndef SANDTIN_SURFACE_COMMON_GLSL
#define SANDTIN_SURFACE_COMMON_GLSL

#include "common.glsl"

layout(std430, binding = 0) readonly buffer Position { vec2 position[]; };
layout(std430, binding = 1) readonly buffer Heights { float height[]; };
layout(std430, binding = 2) readonly buffer RowOffset { uint row_offset[]; };
layout(std430, binding = 3) readonly buffer RowDegree { uint row_degree[]; };
layout(std430, binding = 4) readonly buffer Target { uint target[]; };
layout(std430, binding = 5) readonly buffer EdgeFlags { uint edge_flags[]; };
layout(std430, binding = 6) buffer VertexNormal { vec4 vertex_normal[]; };
layout(std430, binding = 7) readonly buffer Triangles { uint triangles[]; };
layout(std430, binding = 8) readonly buffer SlotFlags { uint slot_flags[]; };
layout(std430, binding = 9) buffer CornerNormal { vec4 corner_normal[]; };
layout(std430, binding = 10) buffer HeightMap { float height_map[]; };
layout(std430, binding = 11) buffer NormalMap { vec4 normal_map[]; };

layout(push_constant) uniform Push {
    uint count;      // vertices or slots to process
    uint mode;       // bake: 0 = smooth vertex normals, 1 = creased corner normals
    uint width;      // bake grid
    uint height;
    float z_scale;   // height exaggeration for normals
    float x0;        // bake: x of sample column 0 minus `offset` cells, relative to the origin
    float y_top;     // bake: y of sample row 0 minus `offset` cells, relative to the origin
    float dx;        // bake: metres per column
    float dy;        // bake: metres per row (rows go south)
    float offset;    // 0.5 for texel centres, 0 for corners
    uint col0;       // bake: only texels with col0 <= col <= col1, row0 <= row <= row1
    uint row0;
    uint col1;
    uint row1;
    uint in_region;  // normals: 1 = only vertices inside the region (origin-relative metres)
    float region_x0;
    float region_y0;
    float region_x1;
    float region_y1;
} pc;

bool outside_region(uint v) {
    if (pc.in_region == 0u) return false;
    vec2 p = position[v];
    return p.x < pc.region_x0 || p.y < pc.region_y0 || p.x > pc.region_x1 || p.y > pc.region_y1;
}

vec3 surface_point(uint v) { return vec3(position[v], height[v] * pc.z_scale); }

// Twice the area vector of the wedge (v, w_k, w_k+1) of v's counter-clockwise ring, or zero
// when that wedge is not a triangle (the outside gap of a border vertex).
vec3 wedge(uint v, uint begin, uint degree, uint k) {
    uint a = target[begin + k];
    uint b = target[begin + (k + 1u) % degree];
    vec3 pv = surface_point(v);
    vec3 ea = surface_point(a) - pv;
    vec3 eb = surface_point(b) - pv;
    if (!(ea.x * eb.y - ea.y * eb.x > 0.0)) return vec3(0.0);
    return cross(ea, eb);
}

bool wedge_exists(uint v, uint begin, uint degree, uint k) {
    uint a = target[begin + k];
    uint b = target[begin + (k + 1u) % degree];
    vec2 ea = position[a] - position[v];
    vec2 eb = position[b] - position[v];
    return ea.x * eb.y - ea.y * eb.x > 0.0;
}

#endif
