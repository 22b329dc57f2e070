#version 450
// Wireframe and constrained-edge lines over the terrain, pulled slightly towards the camera so
// they win the depth test against the surface they lie on.

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 colour;
} pc;

layout(location = 0) in vec3 in_position;

void main() {
    gl_Position = pc.view_projection * vec4(in_position, 1.0);
    gl_Position.z -= 2e-4 * gl_Position.w;
}
