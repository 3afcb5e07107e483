#version 460
// CCIPCA's input (Chen et al. 2012 feed it a 3-ray path tracer): eq 9 from --vpls VPLs per
// pixel drawn afresh every frame (the R2 points turned by a per-pixel, per-frame random angle),
// no accumulation. Writes the noisy image, starts each pixel's residual u_1 = x, counts its
// sample (or restarts it, zeroing the bases; a pixel the warp found no history for has
// count 0 and bases 0 already), and stores the group's sums for basis 0.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#define CCIPCA_BASES
#define CCIPCA_RESIDUAL
#define CCIPCA_PARTIALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D rsm_position;
layout(set = 1, binding = 3) uniform texture2D rsm_normal;
layout(set = 1, binding = 4) uniform texture2D rsm_flux;
layout(set = 1, binding = 5, rgba32f) uniform writeonly image2D noisy;

#include "rsm_gather.glsl"

// A PCG hash (Jarzynski & Olano 2020) of pixel and frame: independent turns per pixel and
// frame, where interleaved gradient noise would repeat its pattern every frame.
float pixel_frame_noise(ivec2 pixel, uint frame_index) {
    uint v = (uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + frame_index * 26699u) | 1u;
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return unorm32((word >> 22u) ^ word);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = !outside_frame(pixel);
    vec4 s[SUM_VEC4S] = NO_SUMS;
    if (inside) {
        vec3 x = vec3(0.0);
        vec4 g = texelFetch(g_position, pixel, 0);
        if (g.w != 0.0) {
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            float seed = pixel_frame_noise(pixel, frame.frame_index);
            x = rsm_gather_sampled(g.xyz, n, frame.frame_index, 0u, frame.vpl_count, seed);
        }
        imageStore(noisy, pixel, vec4(x, 1.0));
        uint p = pixel_index(pixel);
        if (ccipca.restart != 0u) {
            for (uint i = 1u; i < BASES; ++i) bases[basis_index(i, p)] = vec4(0.0);
        }
        vec4 v0 = ccipca.restart != 0u ? vec4(0.0) : bases[p];
        float age = min(v0.a + 1.0, float(ccipca.max_age));
        bases[p] = vec4(v0.rgb, age);
        residual[p] = vec4(x, age);
        pixel_sums(x, v0.rgb, ccipca_step(age, 0u), s);
    }
    store_partials(s, UPDATE_SUM_VEC4S);
}
