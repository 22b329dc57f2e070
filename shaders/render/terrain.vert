#version 450
// Terrain vertex stage (indexed by VertexId): positions relative to the domain centre
// (metres) and the overlay scalars computed on the CPU.

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_dir;  // xyz: towards the light (unit); w: contrast strength in [0, 1]
    vec4 cursor;     // xy: tool centre (m, centre-relative); z: radius (m); w: 1 = show
    vec4 overlays;   // x: bits (1 wireframe; 2, 4, 8 the water's, water.frag), y: active,
                     // z: sand thickness,
                     // w: slope vs repose
    vec4 contrast;   // x: height low, y: height high (m) of the histogram stretch
} pc;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec3 in_overlay;  // x: tan(repose), y: sand thickness (m), z: active
layout(location = 4) in vec2 in_slide;    // texture-sliding offset (texture units)

layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec3 v_albedo;
layout(location = 3) out vec3 v_overlay;
layout(location = 4) out vec2 v_slide;

void main() {
    v_world = in_position;
    v_normal = in_normal;
    v_albedo = in_albedo;
    v_overlay = in_overlay;
    v_slide = in_slide;
    gl_Position = pc.view_projection * vec4(in_position, 1.0);
}
