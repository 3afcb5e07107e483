#version 460
// One iteration of SVGF's edge-avoiding a-trous wavelet (Schied et al. section 4.3): a 5x5
// B3-spline kernel (1/16, 1/4, 3/8, 1/4, 1/16 per axis) whose taps lie `step` pixels apart,
// each weighted by the edge-stopping of depth, normal and luminance, the last scaled by the
// standard deviation of the 3x3-Gaussian-filtered variance. The variance is filtered along
// with the colour, with the squared weights, for the next iteration. The first iteration's
// colour is also the next frame's temporal history (the `feedback` permutation).
// @permutation feedback: FEEDBACK
// @permutation plain: PLAIN
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "svgf.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 10) uniform texture2D depth;
layout(set = 1, binding = 12) uniform texture2D atrous_in;  // rgb, a: variance
layout(set = 1, binding = 13, rgba32f) uniform writeonly image2D atrous_out;
#ifdef FEEDBACK
layout(set = 1, binding = 8, rgba32f) uniform writeonly image2D color;
#endif

// The B3 spline's weights at 0, 1 and 2 taps from the centre.
const float KERNEL[3] = float[3](0.375, 0.25, 0.0625);

bool has_geometry(ivec2 q) {
    return !outside_frame(q) && texelFetch(depth, q, 0).x > 0.0;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 z = texelFetch(depth, pixel, 0).xyz;
    if (z.x == 0.0) {
        imageStore(atrous_out, pixel, vec4(0.0));
        return;
    }
    // The variance's 3x3 Gaussian (1/4, 1/2, 1/4 per axis) over the pixels with geometry.
    float var_sum = 0.0;
    float var_weights = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (!has_geometry(q)) continue;
            float k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
            var_sum += k * texelFetch(atrous_in, q, 0).a;
            var_weights += k;
        }
    }
    vec4 centre = texelFetch(atrous_in, pixel, 0);
    float l_p = svgf_luminance(centre.rgb);
    // The centre's own weight is 1/4: var_weights >= 1/4.
    float sigma = sqrt(max(var_sum / var_weights, 0.0));
    float phi_l = svgf.sigma_luminance * sigma + LUMINANCE_FLOOR * abs(l_p) + LUMINANCE_TINY;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    int step = int(svgf.step);
    vec3 sum = vec3(0.0);
    float var = 0.0;
    float weights = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            ivec2 offset = ivec2(i, j) * step;
            ivec2 q = pixel + offset;
            if (outside_frame(q)) continue;
            float zq = texelFetch(depth, q, 0).x;
            if (zq == 0.0) continue;
            vec4 v = texelFetch(atrous_in, q, 0);
            float w = KERNEL[abs(i)] * KERNEL[abs(j)] *
                      edge_weight(z, l_p, phi_l, n, zq, svgf_luminance(v.rgb), texelFetch(g_normal, q, 0).xyz, vec2(offset));
            sum += w * v.rgb;
            var += w * w * v.a;
            weights += w;
        }
    }
    // The centre weighs about (3/8)^2 (every edge term is 1 there for a unit normal).
    vec4 filtered = weights > 0.0 ? vec4(sum / weights, var / (weights * weights)) : centre;
    imageStore(atrous_out, pixel, filtered);
#ifdef FEEDBACK
    imageStore(color, pixel, vec4(filtered.rgb, 1.0));
#endif
}
