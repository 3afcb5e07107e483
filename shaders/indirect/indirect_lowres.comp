#version 460
// Half-resolution RSM gather with interleaving (without, indirect_spread.comp's `gather` runs
// over the samples indirect_classify.comp lists): over the 16x16 blocks the reprojection
// listed, each workgroup computes the block's 8x8 low-resolution pixels plus a one-pixel apron on the right and
// bottom (9x9) into the block's own slot of the low-resolution buffer, so the upsampling of
// the block reads only values computed this frame. Low-resolution pixel i samples the G-buffer
// at full-resolution texel 2i (the top-left of its 2x2 block), where indirect_upsample.comp's
// weights place it. With interleaving each low-resolution pixel gathers its share of the VPLs,
// put together from the tile's pixels where its full-resolution texel is new (interleave.glsl).
// Pixels of the refresh tile are recomputed by indirect_spread.comp's `refresh_lowres` from
// every pattern of their samples; the samples here hold this frame's pattern like every other,
// for their neighbours.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

#define INTERLEAVE_TILE 9u
layout(local_size_x = INTERLEAVE_TILE, local_size_y = INTERLEAVE_TILE) in;

layout(set = 1, binding = 6, std430) buffer LowRes { vec4 lowres[]; };
layout(set = 1, binding = 7, STATE_FORMAT) uniform readonly uimage2D state_in;

#include "indirect_common.glsl"
#include "interleave.glsl"

shared uint group_computed;

void main() {
    // Uniform over the workgroup: a group past the list returns whole, before any barrier.
    uint group = listed_group();
    if (group >= counters.listed_blocks) return;
    if (gl_LocalInvocationIndex == 0u) group_computed = 0u;
    barrier();
    uint packed = counters.data[group];
    ivec2 block = ivec2(packed & 0xffffu, packed >> 16);
    ivec2 low = block * 8 + ivec2(gl_LocalInvocationID.xy);
    ivec2 low_size = ivec2((frame.size + 1u) / 2u);
    vec4 value = vec4(0.0);
    bool computed = false;
    vec3 p = vec3(0.0);
    vec3 n = vec3(0.0);
    bool is_new = false;
    if (all(greaterThanEqual(low, ivec2(0))) && all(lessThan(low, low_size))) {
        ivec2 full = low * 2;
        vec4 position = texelFetch(g_position, full, 0);
        // Every sample takes part in its neighbours' reconstruction: all are gathered.
        if (position.w != 0.0) {
            computed = true;
            p = position.xyz;
            n = texelFetch(g_normal, full, 0).xyz;
            is_new = imageLoad(state_in, full).r == STATE_NEW;
            value = indirect_share(p, n, low);
            if (planted_nan(full)) value = vec4(quiet_nan());
            atomicAdd(group_computed, 1u);
        }
    }
    // Neighbours one low-resolution pixel (two full ones) apart.
    value = interleave_reconstruct(gl_LocalInvocationID.xy, computed, is_new, p, n, pixel_footprint(p, 2.0), value);
    if (!computed) value = vec4(0.0);
    lowres[group * 81u + gl_LocalInvocationIndex] = value;
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    if (group_computed > 0u) atomicAdd(counters.computed_pixels, group_computed);
    uint shares = vpl_params.interleave * vpl_params.interleave;
    COUNT_WORK(gather, INTERLEAVE_PIXELS, group_computed,
               group_computed > 0u ? (rsm_gather_evaluations() + shares - 1u) / shares : 0u)
}
