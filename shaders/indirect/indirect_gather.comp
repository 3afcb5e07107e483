#version 460
// Full-resolution RSM gather merged into the indirect history when half resolution is off:
// over the listed 16x16 blocks, each new or accumulating pixel with this frame's pattern and
// its interleaved share of the VPLs (interleave.glsl). The refresh tile is
// indirect_spread.comp's.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

layout(set = 1, binding = 6, INDIRECT_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 7, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 8, MOMENTS_FORMAT) uniform image2D moments;

#include "indirect_common.glsl"
#include "indirect_merge.glsl"

#define INTERLEAVE_TILE 16u
layout(local_size_x = INTERLEAVE_TILE, local_size_y = INTERLEAVE_TILE) in;
#include "interleave.glsl"

shared uint group_computed;

void main() {
    if (gl_LocalInvocationIndex == 0u) group_computed = 0u;
    barrier();
    ivec2 pixel = block_pixel(gl_LocalInvocationID.xy);
    bool in_range = !outside_frame(pixel);
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
            fresh = indirect_share(p, n, pixel);
            if (planted_nan(pixel)) fresh = vec4(quiet_nan());
        }
    }
    fresh = interleave_reconstruct(gl_LocalInvocationID.xy, work, is_new, p, n, pixel_footprint(p, 1.0), fresh);
    if (work) atomicAdd(group_computed, 1u);
    if (work) merge(pixel, imageLoad(history, pixel), fresh, false);
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    if (group_computed > 0u) atomicAdd(counters.computed_pixels, group_computed);
    uint vpls = rsm_gather_evaluations();
    COUNT_WORK(gather, INTERLEAVE_PIXELS, group_computed,
               group_computed > 0u ? (vpls + vpl_params.interleave * vpl_params.interleave - 1u) /
                                         (vpl_params.interleave * vpl_params.interleave) : 0u)
}
