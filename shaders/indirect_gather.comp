#version 460
// Full-resolution RSM gather merged into the indirect history. `fixup`: over the list of
// pixels the upsampling discarded, with every VPL; `blocks`: over the listed 16x16 blocks when
// half resolution is off, each pixel with its interleaved share of the VPLs (interleave.glsl);
// both one pattern per new or accumulating pixel. `refresh`: one workgroup per pixel
// of the refresh tile (refresh.glsl) recomputes it at full resolution as the mean of every
// pattern up to the rotation limit, blended in along the tile's feather ramp; it runs last,
// and the other passes leave refresh pixels alone.
// @permutation fixup: FIXUP
// @permutation blocks: BLOCKS
// @permutation refresh: REFRESH
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

layout(set = 1, binding = 6, rgba32f) uniform image2D history;
layout(set = 1, binding = 7, r32ui) uniform readonly uimage2D state_in;
layout(set = 1, binding = 8, rgba32f) uniform image2D moments;

#include "indirect_common.glsl"
#include "indirect_merge.glsl"

#ifdef REFRESH
#include "refresh.glsl"
layout(local_size_x = REFRESH_THREADS) in;

void main() {
    ivec2 pixel = refresh_pixel();
    uint limit = frame.rotation_limit;
    bool refreshed = !outside_frame(pixel) && imageLoad(state_in, pixel).r == STATE_REFRESH;
    vec4 mine = vec4(0.0); // sums of this invocation's patterns (rgb) and squared luminances
    if (refreshed) {
        vec3 p = texelFetch(g_position, pixel, 0).xyz;
        vec3 n = texelFetch(g_normal, pixel, 0).xyz;
        for (uint j = gl_LocalInvocationIndex; j < limit; j += REFRESH_THREADS)
            mine += indirect_pattern(p, n, j, pixel, 1u);
    }
    vec4 total = refresh_sum(mine);
    if (gl_LocalInvocationIndex != 0u || !refreshed) return;
    merge(pixel, imageLoad(history, pixel), total / float(limit), true);
    atomicAdd(counters.computed_pixels, 1u);
    atomicAdd(counters.refresh_evaluations, limit);
}
#else
#ifdef FIXUP
layout(local_size_x = 64) in;
#else
#define INTERLEAVE_TILE 16u
layout(local_size_x = INTERLEAVE_TILE, local_size_y = INTERLEAVE_TILE) in;
#include "interleave.glsl"
#endif

shared uint group_computed;

void main() {
    if (gl_LocalInvocationIndex == 0u) group_computed = 0u;
    barrier();
#ifdef FIXUP
    uint i = gl_GlobalInvocationID.x;
    bool in_range = i < counters.fixup_pixels;
    uint packed = in_range ? counters.data[counters.max_blocks + i] : 0u;
    ivec2 pixel = ivec2(packed & 0xffffu, packed >> 16);
#else
    ivec2 pixel = block_pixel(gl_WorkGroupID.x, gl_LocalInvocationID.xy);
    bool in_range = !outside_frame(pixel);
#endif
    bool work = false;
    vec3 p = vec3(0.0);
    vec3 n = vec3(0.0);
    vec4 fresh = vec4(0.0);
    bool is_new = false;
    if (in_range) {
        uint state = imageLoad(state_in, pixel).r;
        vec4 position = texelFetch(g_position, pixel, 0);
        work = position.w != 0.0 && (state == STATE_NEW || state == STATE_ACCUMULATING);
        is_new = state == STATE_NEW;
        if (work) {
            p = position.xyz;
            n = texelFetch(g_normal, pixel, 0).xyz;
#ifdef FIXUP
            // Discarded pixels have no neighbour on their surface: every VPL.
            fresh = indirect_value(p, n, pixel);
#else
            fresh = indirect_share(p, n, pixel);
#endif
        }
    }
#ifndef FIXUP
    fresh = interleave_reconstruct(gl_LocalInvocationID.xy, work, is_new, p, n, pixel_footprint(p, 1.0), fresh);
    if (work) atomicAdd(group_computed, 1u);
#endif
    if (work) merge(pixel, imageLoad(history, pixel), fresh, false);
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_computed > 0u)
        atomicAdd(counters.computed_pixels, group_computed);
}
#endif
