#version 460
// SSAO with temporal reuse: dispatched indirectly over the 8x8 blocks the reprojection listed;
// evaluates one rotated pattern per pixel that is new or accumulating and merges it into the
// history (temporal.glsl: the gated running mean, eqs 4-5, EMA or capped mean); pixels of the
// refresh tile are recomputed from scratch as the mean of every pattern up to the rotation
// limit, the estimator accumulation converges to, and blended in along the tile's feather ramp
// (refresh_weight). Converged pixels are left alone.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D random_vectors;
layout(set = 1, binding = 3, r32ui) uniform readonly uimage2D state_in;
layout(set = 1, binding = 4, rgba32f) uniform image2D history;
layout(set = 1, binding = 6, rgba32f) uniform image2D moments;

#include "ao.glsl"

shared uint group_computed;
shared uint group_refresh; // pattern evaluations of the refresh tile

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        group_computed = 0u;
        group_refresh = 0u;
    }
    barrier();
    ivec2 pixel = block_pixel(gl_WorkGroupID.x, gl_LocalInvocationID.xy);
    if (!outside_frame(pixel)) {
        uint state = imageLoad(state_in, pixel).r;
        if (state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH) {
            vec3 p = texelFetch(g_position, pixel, 0).xyz;
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            vec4 h = imageLoad(history, pixel);
            uint limit = frame.rotation_limit;
            vec2 result;
            vec4 m = imageLoad(moments, pixel);
            if (state == STATE_REFRESH) {
                atomicAdd(group_refresh, limit);
                // The mean of every pattern and of its square: what accumulation converges to.
                float sum = 0.0;
                float sum2 = 0.0;
                for (uint j = 0u; j < limit; ++j) {
                    float x = 1.0 - ao_estimate(pixel, p, n, float(j), 1u);
                    sum += x;
                    sum2 += x * x;
                }
                float w = refresh_blend(refresh_weight(pixel), h.a, sum2 / float(limit), m);
                result = vec2(mix(h.r, sum / float(limit), w), float(limit));
            } else {
                // Each pixel walks through patterns 0, 1, ... in the order it accumulates them.
                float fresh = 1.0 - ao_estimate(pixel, p, n, h.a, 1u);
                result = accumulate(h.r, h.a, fresh, m);
            }
            imageStore(history, pixel, vec4(clamp(result.x, 0.0, 1.0), 0.0, 0.0, result.y));
            imageStore(moments, pixel, m);
            atomicAdd(group_computed, 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_computed > 0u)
        atomicAdd(counters.computed_pixels, group_computed);
    if (gl_LocalInvocationIndex == 0u && group_refresh > 0u)
        atomicAdd(counters.refresh_evaluations, group_refresh);
}
