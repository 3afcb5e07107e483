#version 460
// Full-resolution RSM gather merged into the indirect history. `fixup`: over the list of
// pixels the upsampling discarded; `blocks`: over the listed 16x16 blocks when half resolution
// is off; both one pattern per new or accumulating pixel. `refresh`: one workgroup per pixel
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
            mine += indirect_pattern(p, n, j, pixel);
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
layout(local_size_x = 16, local_size_y = 16) in;
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
    if (in_range) {
        uint state = imageLoad(state_in, pixel).r;
        vec4 position = texelFetch(g_position, pixel, 0);
        if (position.w != 0.0 && (state == STATE_NEW || state == STATE_ACCUMULATING)) {
            vec4 fresh = indirect_value(position.xyz, texelFetch(g_normal, pixel, 0).xyz, pixel);
            merge(pixel, imageLoad(history, pixel), fresh, false);
#ifndef FIXUP
            atomicAdd(group_computed, 1u);
#endif
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_computed > 0u)
        atomicAdd(counters.computed_pixels, group_computed);
}
#endif
