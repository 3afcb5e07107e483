#version 460
// SVGF's variance estimate (Schied et al. section 4.2): the luminance variance from the
// temporal moments, E[l^2] - E[l]^2, where a pixel has integrated at least 4 samples; with
// fewer, from the moments of its 7x7 neighbourhood weighted by depth and normals (the
// article), raised by 4/n as the authors' implementation does (few samples understate it).
// Writes the a-trous input: the integrated colour and its variance.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "svgf.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 8) uniform texture2D color;
layout(set = 1, binding = 9) uniform texture2D moments;
layout(set = 1, binding = 10) uniform texture2D depth;
layout(set = 1, binding = 12, rgba32f) uniform writeonly image2D integrated; // rgb, a: variance

// Samples from which the temporal moments give the variance (the article: 4).
const float TEMPORAL_SAMPLES = 4.0;
const int SPATIAL_RADIUS = 3;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 z = texelFetch(depth, pixel, 0).xyz;
    if (z.x == 0.0) {
        imageStore(integrated, pixel, vec4(0.0));
        return;
    }
    vec3 m = texelFetch(moments, pixel, 0).rgb;
    vec2 mean = m.yz;
    if (m.x < TEMPORAL_SAMPLES) {
        vec3 n = texelFetch(g_normal, pixel, 0).xyz;
        vec2 sum = vec2(0.0);
        float weights = 0.0;
        for (int dy = -SPATIAL_RADIUS; dy <= SPATIAL_RADIUS; ++dy) {
            for (int dx = -SPATIAL_RADIUS; dx <= SPATIAL_RADIUS; ++dx) {
                ivec2 q = pixel + ivec2(dx, dy);
                if (outside_frame(q)) continue;
                float zq = texelFetch(depth, q, 0).x;
                if (zq == 0.0) continue;
                float w = edge_weight(z, 0.0, 0.0, n, zq, 0.0, texelFetch(g_normal, q, 0).xyz, vec2(dx, dy));
                sum += w * texelFetch(moments, q, 0).yz;
                weights += w;
            }
        }
        // The centre weighs about 1 (a unit normal's pow(n . n, sigma_n)).
        if (weights > 0.0) mean = sum / weights;
    }
    float variance = max(mean.y - mean.x * mean.x, 0.0);
    if (m.x < TEMPORAL_SAMPLES) variance *= TEMPORAL_SAMPLES / max(m.x, 1.0);
    imageStore(integrated, pixel, vec4(texelFetch(color, pixel, 0).rgb, variance));
}
