#version 450
#extension GL_GOOGLE_include_directive : require
// Creased normals per triangle corner (slot * 3 + corner): the area-weighted normal of the fan
// of triangles around the corner's vertex that can be reached from this triangle without
// crossing a constrained edge, so tool walls keep a sharp crease while the rest is smooth.
#include "surface_common.glsl"

vec3 corner(uint v, uint w) {
    uint begin = row_offset[v];
    uint degree = row_degree[v];
    uint k = 0u;
    while (k < degree && target[begin + k] != w) ++k;
    if (k == degree) return vec3(0.0, 0.0, 1.0);  // mirror out of date: cannot happen after sync
    vec3 sum = wedge(v, begin, degree, k);
    uint steps = 0u;
    // Backwards: wedge j-1 joins wedge j across the edge v -> w_j.
    uint j = k;
    while (steps + 1u < degree) {
        if ((edge_flags[begin + j] & 1u) != 0u) break;
        uint jp = (j + degree - 1u) % degree;
        if (!wedge_exists(v, begin, degree, jp)) break;
        sum += wedge(v, begin, degree, jp);
        j = jp;
        ++steps;
    }
    // Forwards: wedge j+1 joins wedge j across the edge v -> w_j+1.
    j = k;
    while (steps + 1u < degree) {
        uint jn = (j + 1u) % degree;
        if ((edge_flags[begin + jn] & 1u) != 0u) break;
        if (!wedge_exists(v, begin, degree, jn)) break;
        sum += wedge(v, begin, degree, jn);
        j = jn;
        ++steps;
    }
    return dot(sum, sum) > 0.0 ? normalize(sum) : vec3(0.0, 0.0, 1.0);
}

void main() {
    uint s = thread_index();
    if (s >= pc.count) return;
    if ((slot_flags[s] & 8u) == 0u) {
        for (uint c = 0u; c < 3u; ++c) corner_normal[3u * s + c] = vec4(0.0, 0.0, 1.0, 0.0);
        return;
    }
    // A region pass recomputes the slots with a corner inside the region.
    if (outside_region(triangles[3u * s]) && outside_region(triangles[3u * s + 1u]) &&
        outside_region(triangles[3u * s + 2u]))
        return;
    for (uint c = 0u; c < 3u; ++c) {
        uint v = triangles[3u * s + c];
        uint w = triangles[3u * s + (c + 1u) % 3u];
        corner_normal[3u * s + c] = vec4(corner(v, w), 0.0);
    }
}
