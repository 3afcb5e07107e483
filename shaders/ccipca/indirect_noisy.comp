#version 460
// The noisy input of the filters that replace the thesis's accumulation (Chen et al. 2012 feed
// theirs a 3-ray path tracer): eq 9 from --vpls VPLs per pixel drawn afresh every frame (the
// R2 points turned by a per-pixel, per-frame random angle), no accumulation. `ccipca` also
// starts each pixel's residual u_1 = x, counts its sample (or restarts it, zeroing the bases;
// a pixel the warp found no history for has count 0 and bases 0 already), and stores the
// group's sums for basis 0, and gathers --ccipca-new-pixel-vpls VPLs where the warp found no
// history (counted as that many regular samples, so the next ones take small steps); `plain` only writes the image (the joint bilateral filters).
// @permutation ccipca: CCIPCA
// @permutation plain: PLAIN
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#ifdef CCIPCA
#define CCIPCA_BASES
#define CCIPCA_RESIDUAL
#define CCIPCA_PARTIALS
#include "ccipca.glsl"
#endif

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D rsm_position;
layout(set = 1, binding = 3) uniform texture2D rsm_normal;
layout(set = 1, binding = 4) uniform texture2D rsm_flux;
layout(set = 1, binding = 5, rgba32f) uniform writeonly image2D noisy;

#include "rsm_gather.glsl"

// A PCG hash (Jarzynski & Olano 2020) of pixel and frame, used as the gather's pattern: its
// radial shift and its rotation then differ from pixel to pixel and frame to frame. (One
// pattern per frame turned per pixel would give every pixel the same radii: with few VPLs
// whole frames would light up or go dark together.)
uint pixel_frame_pattern(ivec2 pixel, uint frame_index) {
    uint v = (uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + frame_index * 26699u) | 1u;
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// --noisy-half-res: the 2x2 block's pixel that gathers this frame (each pixel in turn, over 4
// frames); the others take its sample where they lie on its surface (the upsampling's test:
// normals within 25 degrees, tangent-plane distance within 2 pixel footprints) and gather
// themselves elsewhere.
ivec2 block_gatherer(ivec2 pixel) {
    const ivec2 ORDER[4] = ivec2[](ivec2(0, 0), ivec2(1, 1), ivec2(1, 0), ivec2(0, 1));
    return (pixel & ~1) + ORDER[frame.frame_index % 4u];
}

// This workgroup's gatherers' samples, one per 2x2 block of the 16x16 group.
shared vec3 block_sample[8][8];

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = !outside_frame(pixel);
#ifdef CCIPCA
    vec4 s[SUM_VEC4S] = NO_SUMS;
#endif
    vec3 x = vec3(0.0);
    // The sample's weight in the pixel's count: its VPLs over the regular gather's.
    float weight = 1.0;
    vec4 g = inside ? texelFetch(g_position, pixel, 0) : vec4(0.0);
    vec3 n = inside ? texelFetch(g_normal, pixel, 0).xyz : vec3(0.0);
    bool half_res = vpl_params.noisy_half_res != 0u;
    ivec2 gatherer = block_gatherer(pixel);
    bool own = g.w != 0.0 && (!half_res || pixel == gatherer);
    uint count = vpl_params.count;
#ifdef CCIPCA
    // Adaptive sampling (Chen et al. Figure 6d): a pixel the warp found no history for (no
    // samples, after a camera move) starts from more VPLs.
    if (inside && ccipca.restart == 0u && ccipca.new_pixel_vpls != 0u &&
        bases[pixel_index(pixel)].a == 0.0) {
        count = ccipca.new_pixel_vpls;
        weight = float(count) / float(max(vpl_params.count, 1u));
    }
#endif
    if (own) {
        x = rsm_gather_sampled(g.xyz, n, pixel_frame_pattern(pixel, frame.frame_index), 0u, count, 0.0);
    }
    if (half_res) {
        uvec2 b = gl_LocalInvocationID.xy / 2u;
        if (pixel == gatherer) block_sample[b.x][b.y] = x;
        barrier();
        if (g.w != 0.0 && pixel != gatherer) {
            vec4 gq = outside_frame(gatherer) ? vec4(0.0) : texelFetch(g_position, gatherer, 0);
            vec3 nq = gq.w != 0.0 ? texelFetch(g_normal, gatherer, 0).xyz : vec3(0.0);
            float footprint = 2.0 * distance(g.xyz, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y);
            bool same = gq.w != 0.0 && dot(nq, n) >= 0.9 && abs(dot(n, gq.xyz - g.xyz)) <= 2.0 * footprint;
            x = same ? block_sample[b.x][b.y]
                     : rsm_gather_sampled(g.xyz, n, pixel_frame_pattern(pixel, frame.frame_index), 0u, count, 0.0);
        }
    }
    if (planted_nan(pixel)) x = vec3(quiet_nan());
    // A NaN or infinite sample would make CCIPCA's image-wide sums NaN: it counts as 0, in
    // the stored sample and in this frame's residual and sums alike.
    x = finite_or_zero(x);
    if (inside) {
        imageStore(noisy, pixel, vec4(x, 1.0));
#ifdef CCIPCA
        uint p = pixel_index(pixel);
        if (ccipca.restart != 0u) {
            for (uint i = 1u; i < BASES; ++i) bases[basis_index(i, p)] = vec4(0.0);
        }
        vec4 v0 = ccipca.restart != 0u ? vec4(0.0) : bases[p];
        float age = min(v0.a + weight, float(ccipca.max_age));
        bases[p] = vec4(v0.rgb, age);
        // The count this frame's steps are taken from (residual.a): for a sample worth w
        // regular ones, (n + l) / w - l, so that the step (1 + l) / (count + l) becomes
        // w (1 + l) / (n + l), capped at 1 by ccipca_step: the running mean's step for a
        // weighted sample (a new pixel's first sample replaces its zero bases whatever w is).
        float step_count = (age + ccipca.amnesic) / weight - ccipca.amnesic;
        residual[p] = vec4(x, step_count);
        pixel_sums(x, v0.rgb, ccipca_step(step_count, 0u), s);
#endif
    }
#ifdef CCIPCA
    store_partials(s, UPDATE_SUM_VEC4S);
#endif
}
