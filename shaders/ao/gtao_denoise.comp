#version 460
// GTAO's own spatial denoise without the cache (XeGTAO filters its noisy output the same way,
// edge-aware, before any temporal step): gtao_denoise.glsl's 5x5 edge-aware weights over the
// raw AO.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "gtao_denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D ao_in;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D ao_out;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 g = texelFetch(g_position, pixel, 0);
    if (g.w == 0.0) {
        imageStore(ao_out, pixel, texelFetch(ao_in, pixel, 0));
        return;
    }
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float inv_plane = gtao_denoise_inv_plane(g.xyz);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (outside_frame(q)) continue;
            vec4 gq = texelFetch(g_position, q, 0);
            if (gq.w == 0.0) continue;
            float w = gtao_denoise_weight(ivec2(i, j), g.xyz, n, inv_plane, gq.xyz,
                                          texelFetch(g_normal, q, 0).xyz);
            sum += w * texelFetch(ao_in, q, 0);
            weights += w;
        }
    }
    // The centre weighs 4 (its normal and plane agree with themselves): weights >= 4.
    imageStore(ao_out, pixel, sum / max(weights, 1.0));
}
