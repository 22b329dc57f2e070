#version 450
#extension GL_GOOGLE_include_directive : require
// Smooth per-vertex normals: the area-weighted mean of the incident triangles' normals (sum
// of their cross products), unit length; (0, 0, 1) for dead ids. maps/vertex_normals.cpp is
// the CPU twin. With pc.in_region only vertices inside the region are recomputed (a re-bake
// after a local change).
#include "surface_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.count || outside_region(v)) return;
    uint degree = row_degree[v];
    vec3 n = vec3(0.0);
    uint begin = row_offset[v];
    for (uint k = 0u; k < degree; ++k) n += wedge(v, begin, degree, k);
    vertex_normal[v] = dot(n, n) > 0.0 ? vec4(normalize(n), 0.0) : vec4(0.0, 0.0, 1.0, 0.0);
}
