#version 450
#extension GL_GOOGLE_include_directive : require
// Before a run: water at least wet_depth deep wets the sand under it to wet_moisture
// (water/live_water.hpp's LiveWaterSettings::wet_depth and wet_moisture), never drying it.
#include "moisture_common.glsl"

void main() {
    uint v = thread_index();
    if (v >= pc.vertex_count) return;
    if (area[v] > 0.0 && depth[v] >= pc.wet_depth && moisture[v] < pc.wet_moisture)
        moisture[v] = pc.wet_moisture;
}
