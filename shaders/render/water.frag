#version 450
// Water surface shading, blended over the terrain already drawn (premultiplied alpha, no
// depth write): what the surface reflects (the sky, by Schlick's Fresnel term for water,
// F0 = 0.02, and the sun's glint) plus the light the water body scatters back, over the bed
// seen through it, dimmed by absorption along the view path through the depth (Beer-Lambert,
// e-folding at 2 cm for blue-green light in sandy water). Shallow water is nearly clear, deep
// water opaque blue-green; films under half a millimetre fade into the wet sand. The water
// overlays (depth, speed, sediment) colour the surface itself.

layout(push_constant) uniform Push {
    mat4 view_projection;
    vec4 light_dir;
    vec4 eye;
    vec4 overlays;
    vec4 unused;
} pc;

layout(location = 0) in vec3 v_surface;
layout(location = 1) in float v_water;     // m, linear across the face; < 0 under a bank
layout(location = 2) in float v_speed;     // m/s
layout(location = 3) in float v_sediment;  // sand per volume of water

layout(location = 0) out vec4 out_colour;

void main() {
    if (v_water <= 0.0) discard;
    // The surface is piecewise linear: its face normal from the position's derivatives.
    vec3 n = normalize(cross(dFdx(v_surface), dFdy(v_surface)));
    if (n.z < 0.0) n = -n;
    vec3 to_eye = normalize(pc.eye.xyz - v_surface);
    float cos_view = clamp(dot(n, to_eye), 0.0, 1.0);
    float fresnel = 0.02 + 0.98 * pow(1.0 - cos_view, 5.0);
    // Refraction bends the view towards the normal (sin t = sin i / 1.33): the path down to
    // the bed and back up is depth / cos t.
    float sin_t = sqrt(max(1.0 - cos_view * cos_view, 0.0)) / 1.33;
    float cos_t = sqrt(max(1.0 - sin_t * sin_t, 0.05));
    float absorbed = 1.0 - exp(-v_water / cos_t / 0.02);
    vec3 body = vec3(0.03, 0.16, 0.24);  // what deep sandy water scatters back
    vec3 sky = mix(vec3(0.62, 0.72, 0.84), vec3(0.32, 0.48, 0.72), cos_view);
    vec3 l = normalize(pc.light_dir.xyz);
    float glint = pow(max(dot(n, normalize(l + to_eye)), 0.0), 300.0) * 1.5;
    // Premultiplied: the bed behind keeps (1 - alpha) of its light.
    vec3 colour = (1.0 - fresnel) * absorbed * body + fresnel * sky + vec3(glint);
    float alpha = 1.0 - (1.0 - fresnel) * (1.0 - absorbed);
    // A faint tint even where the water is clear, so a shallow sheet reads as water.
    colour += (1.0 - alpha) * vec3(0.0, 0.025, 0.04);
    alpha = max(alpha, 0.12);

    int bits = int(pc.overlays.x + 0.5);
    vec3 ramp = vec3(0.0);
    bool overlay = false;
    if ((bits & 2) != 0) {
        // Water depth: 0 .. 5 cm from pale cyan to deep blue.
        ramp = mix(vec3(0.6, 0.95, 1.0), vec3(0.0, 0.1, 0.6), clamp(v_water / 0.05, 0.0, 1.0));
        overlay = true;
    }
    if ((bits & 4) != 0) {
        // Speed on a log scale, as speeds span orders of magnitude: 1 mm/s or less dark blue,
        // then cyan (3 cm/s), yellow, and red at 1 m/s or more.
        float s = clamp(log(max(v_speed, 1e-4) / 0.001) / log(1000.0), 0.0, 1.0);
        ramp = s < 0.5 ? mix(vec3(0.05, 0.1, 0.45), vec3(0.1, 0.85, 0.9), s * 2.0)
                       : mix(vec3(0.95, 0.9, 0.1), vec3(0.9, 0.1, 0.05), s * 2.0 - 1.0);
        overlay = true;
    }
    if ((bits & 8) != 0) {
        // Sediment: clear water pale blue, turning muddy brown as the sand it carries reaches
        // 5 % of its volume (the law allows 30 %: a slurry, rarely reached).
        ramp = mix(vec3(0.55, 0.8, 0.95), vec3(0.45, 0.25, 0.08), clamp(v_sediment / 0.05, 0.0, 1.0));
        overlay = true;
    }
    if (overlay) {
        // An overlay reads as its colour: nearly opaque, whatever the depth.
        colour = 0.8 * ramp + 0.2 * colour;
        alpha = 0.8 + 0.2 * alpha;
    }
    // Films fade into the wet sand over their last half millimetre.
    float shore = smoothstep(0.0, 5e-4, v_water);
    out_colour = vec4(colour, alpha) * shore;
}
