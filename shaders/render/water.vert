#version 450
// Water surface vertex stage, drawn only over the triangles with a wet corner
// (TerrainMesh::water_indices): a wet vertex raised by its water; a dry corner at its wet
// neighbours' level where its bank rises above it (RenderVertex::surface), so the surface runs
// level under the bank, which hides it: the waterline is where the water's plane meets the
// sand. v_water, the surface over the bed, is the depth across the face and negative under
// the bank.

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_dir;  // xyz: towards the light (unit)
    vec4 eye;        // xyz: the camera (m, domain-centre relative)
    vec4 overlays;   // x: bits (2 water depth, 4 water speed, 8 sediment)
    vec4 unused;
} pc;

layout(location = 0) in vec3 in_position;
layout(location = 5) in float in_water;     // water depth (m)
layout(location = 6) in float in_speed;     // water flow speed (m/s)
layout(location = 7) in float in_sediment;  // sand carried per volume of water
layout(location = 8) in float in_surface;   // the water's surface height (m)

layout(location = 0) out vec3 v_surface;
layout(location = 1) out float v_water;
layout(location = 2) out float v_speed;
layout(location = 3) out float v_sediment;

void main() {
    v_surface = vec3(in_position.xy, in_surface);
    v_water = in_surface - in_position.z;
    v_speed = in_speed;
    v_sediment = in_sediment;
    gl_Position = pc.view_projection * vec4(v_surface, 1.0);
}
