#version 450
#extension GL_GOOGLE_include_directive : require
// Height-map and normal-map bake: each invocation rasterises one triangle slot onto the map
// grid (samples inside or on the triangle, barycentric interpolation). Normals interpolate the
// vertex normals (mode 0) or the creased corner normals (mode 1) and are renormalised, so long
// TIN edges shade smoothly. Samples on a shared edge get the same value from both triangles
// up to rounding.
#include "surface_common.glsl"

float orient(vec2 a, vec2 b, vec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

void main() {
    uint s = thread_index();
    if (s >= pc.count || (slot_flags[s] & 8u) == 0u) return;
    uint ia = triangles[3u * s], ib = triangles[3u * s + 1u], ic = triangles[3u * s + 2u];
    vec2 a = position[ia], b = position[ib], c = position[ic];
    float area2 = orient(a, b, c);
    if (!(area2 > 0.0)) return;
    float cmin = (min(a.x, min(b.x, c.x)) - pc.x0) / pc.dx - pc.offset;
    float cmax = (max(a.x, max(b.x, c.x)) - pc.x0) / pc.dx - pc.offset;
    float rmin = (pc.y_top - max(a.y, max(b.y, c.y))) / pc.dy - pc.offset;
    float rmax = (pc.y_top - min(a.y, min(b.y, c.y))) / pc.dy - pc.offset;
    // Clipped to the grid and to the texel rectangle being re-baked.
    int c0 = max(int(pc.col0), int(ceil(cmin - 1e-3)));
    int c1 = min(int(min(pc.col1, pc.width - 1u)), int(floor(cmax + 1e-3)));
    int r0 = max(int(pc.row0), int(ceil(rmin - 1e-3)));
    int r1 = min(int(min(pc.row1, pc.height - 1u)), int(floor(rmax + 1e-3)));
    // Outside the texel rectangle (most triangles, when a band of a new map is baked): done
    // before the normals and heights are fetched.
    if (c0 > c1 || r0 > r1) return;
    vec3 na, nb, nc;
    if (pc.mode == 1u) {
        na = corner_normal[3u * s].xyz;
        nb = corner_normal[3u * s + 1u].xyz;
        nc = corner_normal[3u * s + 2u].xyz;
    } else {
        na = vertex_normal[ia].xyz;
        nb = vertex_normal[ib].xyz;
        nc = vertex_normal[ic].xyz;
    }
    float ha = height[ia], hb = height[ib], hc = height[ic];
    const float eps = 1e-5;
    for (int row = r0; row <= r1; ++row) {
        float y = pc.y_top - (float(row) + pc.offset) * pc.dy;
        for (int col = c0; col <= c1; ++col) {
            vec2 p = vec2(pc.x0 + (float(col) + pc.offset) * pc.dx, y);
            float wa = orient(b, c, p) / area2;
            float wb = orient(c, a, p) / area2;
            float wc = 1.0 - wa - wb;
            if (wa < -eps || wb < -eps || wc < -eps) continue;
            uint texel = uint(row) * pc.width + uint(col);
            height_map[texel] = wa * ha + wb * hb + wc * hc;
            vec3 n = wa * na + wb * nb + wc * nc;
            normal_map[texel] = vec4(dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0), 0.0);
        }
    }
}
