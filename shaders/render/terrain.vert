#version 450
// Terrain vertex stage: positions relative to the domain centre (metres), a per-corner
// barycentric coordinate for the wireframe, and the overlay scalars computed on the CPU.

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_dir;        // xyz: towards the light (unit); w: contrast strength in [0, 1]
    vec4 cursor;           // xy: tool centre (m, centre-relative); z: radius (m); w: 1 = show
    vec4 overlays;         // x: wireframe, y: active, z: sand thickness, w: slope vs repose
    vec4 contrast;         // x: height low, y: height high (m) of the histogram stretch
} pc;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec3 in_bary;      // (1,0,0), (0,1,0), (0,0,1) at the corners
layout(location = 4) in vec4 in_overlay;   // x: constrained-edge mask, y: slope / repose,
                                           // z: sand thickness (m), w: active (0 / 1)
layout(location = 5) in vec2 in_slide;     // texture-sliding offset (texture units)

layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec3 v_albedo;
layout(location = 3) out vec3 v_bary;
layout(location = 4) flat out float v_edge_mask;
layout(location = 5) out vec3 v_overlay;
layout(location = 6) out vec2 v_slide;

void main() {
    v_world = in_position;
    v_normal = in_normal;
    v_albedo = in_albedo;
    v_bary = in_bary;
    v_edge_mask = in_overlay.x;
    v_overlay = in_overlay.yzw;
    v_slide = in_slide;
    gl_Position = pc.view_projection * vec4(in_position, 1.0);
}
