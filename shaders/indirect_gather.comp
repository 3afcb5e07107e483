#version 460
// Full-resolution RSM gather merged into the indirect history: over the fix-up list of pixels
// the upsampling discarded, or over the listed 16x16 blocks when half resolution is off.
// @permutation fixup: FIXUP
// @permutation blocks: BLOCKS
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

#ifdef FIXUP
layout(local_size_x = 64) in;
#else
layout(local_size_x = 16, local_size_y = 16) in;
#endif

layout(set = 1, binding = 6, rgba32f) uniform image2D history;
layout(set = 1, binding = 7, r32ui) uniform readonly uimage2D state_in;
layout(set = 1, binding = 8, rgba32f) uniform image2D moments;

#include "indirect_common.glsl"
#include "indirect_merge.glsl"

shared uint group_computed;
shared uint group_refresh; // pattern evaluations of the refresh tile

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        group_computed = 0u;
        group_refresh = 0u;
    }
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
        if (position.w != 0.0 &&
            (state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH)) {
            bool refresh = state == STATE_REFRESH;
            if (refresh) atomicAdd(group_refresh, frame.rotation_limit);
            vec4 fresh = indirect_value(position.xyz, texelFetch(g_normal, pixel, 0).xyz, refresh, pixel);
            merge(pixel, imageLoad(history, pixel), fresh, refresh);
#ifndef FIXUP
            atomicAdd(group_computed, 1u);
#endif
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_computed > 0u)
        atomicAdd(counters.computed_pixels, group_computed);
    if (gl_LocalInvocationIndex == 0u && group_refresh > 0u)
        atomicAdd(counters.refresh_evaluations, group_refresh);
}
