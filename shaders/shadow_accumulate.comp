#version 460
// PCF soft shadows with temporal reuse (Lin 2013 section 3.4): over the 8x8 blocks the
// reprojection listed, one disc pattern (patterns.glsl) per pixel that is new or
// accumulating, merged into the history (temporal.glsl); the refresh tile is recomputed as the
// mean of every pattern up to the rotation limit, the estimator accumulation converges to, and
// blended in along the tile's feather ramp (refresh_weight).
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
layout(set = 1, binding = 2) uniform texture2D shadow_depth;
layout(set = 1, binding = 3, r32ui) uniform readonly uimage2D state_in;
layout(set = 1, binding = 4, rgba32f) uniform image2D history;
layout(set = 1, binding = 6, rgba32f) uniform image2D moments;

#include "shadow.glsl"

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
                float sum = 0.0;
                float sum2 = 0.0;
                for (uint j = 0u; j < limit; ++j) {
                    float x = shadow_visibility(p, n, float(j), pixel);
                    sum += x;
                    sum2 += x * x;
                }
                float w = refresh_blend(refresh_weight(pixel), h.a, sum2 / float(limit), m);
                result = vec2(mix(h.r, sum / float(limit), w), float(limit));
            } else {
                float fresh = shadow_visibility(p, n, h.a, pixel);
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
