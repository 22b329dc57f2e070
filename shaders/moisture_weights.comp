#version 450
#extension GL_GOOGLE_include_directive : require
// Once per re-triangulation: each vertex's sum of cotangent weights over the edges to
// vertices with an area (moisture_diffusion.cpp's weight_sum; a non-Delaunay edge counts 0)
// and its ratio A / sum, from which the host picks the sub-step.
#include "moisture_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    float av = area[v];
    uint begin = row_offset[v];
    uint end = begin + row_degree[v];
    precise float sum = 0.0;
    if (av > 0.0) {
        for (uint k = begin; k < end; ++k)
            if (area[target[k]] > 0.0) sum += conductance(v, k, begin, end);
    }
    weight_sum[v] = sum;
    ratio[v] = sum > 0.0 ? av / sum : uintBitsToFloat(0x7f800000u);  // +inf
}
