#version 460
// Geometry-aware upsampling of the half-resolution gather (Lin 2013 section 4): each
// full-resolution pixel that needs work tests the low-resolution samples that carry bilinear
// weight at its position (one, two or four; `same_surface`: normal within ~25 degrees, and on
// the pixel's tangent plane within two pixel footprints) and interpolates bilinearly from the
// accepted ones; a pixel with none is discarded, marked in the mask (Figure 4.1) and appended to the fix-up list for a full-resolution gather.
// `image`: the samples are in the low-resolution image (indirect_lowres.comp's `compact`);
// `slots`: in each listed block's 9x9 slot of the low-resolution buffer (`blocks`).
// @permutation image: IMAGE
// @permutation slots: SLOTS
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

#ifdef IMAGE
layout(set = 1, binding = 6, rgba32f) uniform readonly image2D lowres;
#else
layout(set = 1, binding = 6, std430) readonly buffer LowRes { vec4 lowres[]; };
#endif
layout(set = 1, binding = 7, INDIRECT_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 8, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 9, r32ui) uniform writeonly uimage2D discard_mask;
layout(set = 1, binding = 10, MOMENTS_FORMAT) uniform image2D moments;

#include "indirect_common.glsl"
#include "indirect_merge.glsl"

void main() {
    uint group = listed_group();
    if (group >= counters.listed_blocks) return;
    uint packed = counters.data[group];
    ivec2 block = ivec2(packed & 0xffffu, packed >> 16);
    ivec2 pixel = block * 16 + ivec2(gl_LocalInvocationID.xy);
    if (outside_frame(pixel)) return;
    uint state = imageLoad(state_in, pixel).r;
    if (state == STATE_REFRESH) { // recomputed by indirect_spread.comp's refresh
        imageStore(discard_mask, pixel, uvec4(0u));
        return;
    }
    if (state != STATE_NEW && state != STATE_ACCUMULATING) return;
    vec3 p = texelFetch(g_position, pixel, 0).xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float footprint = pixel_footprint(p, 1.0);
    // Low-resolution pixel i holds the sample of full-resolution texel 2i, so in low-resolution
    // units this pixel sits at pixel / 2: an even pixel is its own sample (weight 1), an odd
    // one lies halfway between two samples. Neighbours base + 0..1 stay inside the block's 9x9
    // slot.
    ivec2 base = pixel >> 1;
    vec2 w = vec2(pixel & 1) * 0.5;
    ivec2 low_size = ivec2((frame.size + 1u) / 2u);
    ivec2 apron_origin = block * 8;
    vec4 sum = vec4(0.0);
    float weight_sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 low = base + o;
        float weight = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        // Only samples that carry weight count: an accepted zero-weight one must not keep a
        // pixel whose weighted samples were all rejected from the fix-up.
        if (weight == 0.0 || any(greaterThanEqual(low, low_size))) continue;
        vec4 g = texelFetch(g_position, low * 2, 0);
        if (g.w == 0.0) continue;
        if (!same_surface(p, n, g.xyz, texelFetch(g_normal, low * 2, 0).xyz, footprint)) continue;
#ifdef IMAGE
        sum += weight * imageLoad(lowres, low);
#else
        ivec2 local = low - apron_origin;
        sum += weight * lowres[group * 81u + uint(local.y * 9 + local.x)];
#endif
        weight_sum += weight;
    }
    bool discarded = weight_sum <= 0.0;
    imageStore(discard_mask, pixel, uvec4(discarded ? 1u : 0u));
    if (discarded) {
        uint slot = atomicAdd(counters.fixup_pixels, 1u);
        counters.data[counters.max_blocks + slot] = uint(pixel.x) | (uint(pixel.y) << 16);
        // indirect_spread.comp's `fixup` takes SPREAD_LANES / L pixels per workgroup; past
        // the device's maxComputeWorkGroupCount[0] its workgroups stride over the list.
        uint per_group = SPREAD_LANES / vpl_params.spread_lanes;
        if (slot % per_group == 0u && slot / per_group < max(frame.max_groups_x, 1u))
            atomicAdd(counters.fixup_dispatch_x, 1u);
        return;
    }
    merge(pixel, imageLoad(history, pixel), sum / weight_sum, false);
}
