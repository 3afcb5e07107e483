#version 460
// Joint bilateral filter of the noisy indirect light (the geometry-aware baselines of Chen et
// al.'s comparison: 11x11 and 17x17 windows): every pixel of the (2 RADIUS + 1)^2 window
// weighted by a Gaussian of its screen distance (sigma = RADIUS / 2, so the window spans 2
// sigma), by its normal's agreement (max(0, n . n_q)^16: 0.2 at 25 degrees) and by its
// distance from the centre's tangent plane in pixel footprints (a Gaussian of sigma 2, as
// scale-free as the upsampling's test). Within one frame only: no temporal coherence.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

// Half the window's side: 5 (11x11) or 8 (17x17).
layout(constant_id = 0) const int RADIUS = 5;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 5) uniform texture2D noisy;
layout(set = 1, binding = 10, rgba32f) uniform writeonly image2D filtered;

const float NORMAL_POWER = 16.0;
const float PLANE_SIGMA = 2.0; // pixel footprints

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 g = texelFetch(g_position, pixel, 0);
    if (g.w == 0.0) {
        imageStore(filtered, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float footprint = 2.0 * distance(g.xyz, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y);
    float inv_plane = 1.0 / max(PLANE_SIGMA * footprint, 1e-30);
    // Through a variable: naga does not parse operations on specialization constants.
    int r = RADIUS;
    float sigma = 0.5 * float(r);
    float inv_2s2 = 1.0 / (2.0 * sigma * sigma);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (outside_frame(q)) continue;
            vec4 gq = texelFetch(g_position, q, 0);
            if (gq.w == 0.0) continue;
            float plane = dot(n, gq.xyz - g.xyz) * inv_plane;
            float w = exp(-float(dx * dx + dy * dy) * inv_2s2 - plane * plane) *
                      pow(max(dot(n, texelFetch(g_normal, q, 0).xyz), 0.0), NORMAL_POWER);
            sum += w * texelFetch(noisy, q, 0).rgb;
            weights += w;
        }
    }
    // The centre always weighs 1: weights >= 1.
    imageStore(filtered, pixel, vec4(sum / max(weights, 1.0), 1.0));
}
