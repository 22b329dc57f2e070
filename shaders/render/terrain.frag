#version 450
// Terrain shading: the baked normal map (smooth normals of the TIN, sampled by world xy, so
// long edges show no facets) perturbed by a procedural sand-grain detail normal whose texture coordinates slide with the material (texture-sliding offsets), the
// material albedo, a contrast curve (histogram stretch of the height range, seed 004 §5.2.4),
// optional overlays and the tool cursor ring. The wireframe is a separate line pass, and
// the water a surface drawn over this one (water.vert, water.frag).

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_dir;
    vec4 cursor;
    vec4 overlays;
    vec4 contrast;
} pc;

layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec3 v_albedo;
layout(location = 3) in vec3 v_overlay;  // x: tan(repose), y: sand thickness, z: active
layout(location = 4) in vec2 v_slide;

layout(location = 0) out vec4 out_colour;

// Baked on the GPU over the domain (TerrainNormalMap): x and y of the unit normal, row 0 =
// north edge.
layout(set = 0, binding = 0) uniform sampler2D normal_map;

// Integer hash (no transcendental functions: cheap on software rasterisers).
float hash(vec2 p) {
    uvec2 q = uvec2(ivec2(floor(p)) + 32768);
    uint h = q.x * 1597334677u ^ q.y * 3812015801u;
    h = (h ^ (h >> 16)) * 2246822519u;
    return float(h >> 8) * (1.0 / 16777216.0);
}

float value_noise(vec2 p) {
    vec2 i = floor(p);
    vec2 f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    return mix(mix(hash(i), hash(i + vec2(1, 0)), u.x), mix(hash(i + vec2(0, 1)), hash(i + vec2(1, 1)), u.x), u.y);
}

// Bump mapping from screen-space derivatives (Mikkelsen 2010): perturbs the normal by the
// gradient of a height field h over the surface, with one evaluation of h per pixel.
vec3 bump(vec3 n, vec3 position, float h) {
    vec3 dpdx = dFdx(position);
    vec3 dpdy = dFdy(position);
    vec3 r1 = cross(dpdy, n);
    vec3 r2 = cross(n, dpdx);
    float det = dot(dpdx, r1);
    vec3 grad = sign(det) * (dFdx(h) * r1 + dFdy(h) * r2);
    return normalize(abs(det) * n - grad);
}

void main() {
    // contrast.zw = 1 / domain size: centre-relative position -> texture coordinates.
    vec2 map_uv = vec2(0.5 + v_world.x * pc.contrast.z, 0.5 - v_world.y * pc.contrast.w);
    vec2 nxy = texture(normal_map, map_uv).xy;  // z > 0: the terrain is a height field
    // x = -1 is the renderer's placeholder while the baked map is not ready
    // (vertex_normal_placeholder.hpp): the interpolated vertex normal, the same smooth normal.
    vec3 n = nxy.x <= -0.99999 ? normalize(v_normal)
                               : normalize(vec3(nxy, sqrt(max(1.0 - dot(nxy, nxy), 0.0))));
    // Detail normal: sand grains about 2.5 mm across, offset by the sliding texture
    // coordinates so the grain pattern moves with transported material.
    vec2 uv = v_world.xy * 400.0 + v_slide * 64.0;
    float grains = value_noise(uv) + 0.5 * value_noise(uv * 2.7 + 17.0);
    n = bump(n, v_world, grains * 0.0006);

    vec3 l = normalize(pc.light_dir.xyz);
    float diffuse = max(dot(n, l), 0.0);
    float grain = 0.88 + 0.16 * grains;
    // Sun plus a blue-ish sky term that keeps shadowed slopes readable.
    float sky = 0.5 + 0.5 * n.z;
    vec3 colour = v_albedo * grain * (vec3(1.0, 0.97, 0.9) * diffuse + vec3(0.16, 0.18, 0.22) * sky);

    // Contrast curve: stretch the visible height range and blend it in as shading.
    float span = max(pc.contrast.y - pc.contrast.x, 1e-6);
    float t = clamp((v_world.z - pc.contrast.x) / span, 0.0, 1.0);
    float curve = t * t * (3.0 - 2.0 * t);
    colour *= mix(1.0, 0.6 + 0.6 * curve, pc.light_dir.w);

    if (pc.overlays.y > 0.5 && v_overlay.z > 0.5) colour = mix(colour, vec3(1.0, 0.2, 0.1), 0.6);
    if (pc.overlays.z > 0.5) {
        float s = clamp(v_overlay.y / 0.05, 0.0, 1.0);  // 0 .. 5 cm of sand
        colour = mix(colour, mix(vec3(0.1, 0.2, 0.8), vec3(0.9, 0.9, 0.2), s), 0.5);
    }
    if (pc.overlays.w > 0.5) {
        // The face's own gradient, from its plane: v_world varies linearly over the triangle,
        // so its screen-space derivatives span the face's plane and their cross product is the
        // face's normal (|grad z| = |n_xy| / |n_z|). The rest criterion is per face
        // (physics/face_slopes.hpp, with the same tolerance): a pile whose edges are all at
        // repose can hold faces far steeper, which a per-vertex slope would hide.
        vec3 face = cross(dFdx(v_world), dFdy(v_world));
        float steep = length(face.xy) / max(abs(face.z), 1e-20);
        float r = steep / max(v_overlay.x, 1e-6);  // against tan(repose) across the face
        vec3 c = r < 0.8 ? vec3(0.2, 0.7, 0.3) : (r <= 1.001 ? vec3(0.95, 0.8, 0.1) : vec3(0.9, 0.1, 0.1));
        colour = mix(colour, c, 0.55);
    }
    if (pc.cursor.w > 0.5) {
        float d = length(v_world.xy - pc.cursor.xy);
        float w = max(fwidth(d), 1e-5) * 1.5;
        float ring = 1.0 - smoothstep(0.0, w, abs(d - pc.cursor.z));
        float dot_ = 1.0 - smoothstep(0.0, w, d - pc.cursor.z * 0.06);
        colour = mix(colour, vec3(0.1, 0.9, 1.0), max(ring, dot_));
    }
    out_colour = vec4(colour, 1.0);
}
