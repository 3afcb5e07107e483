#version 460
// PCF soft shadows with temporal reuse (Lin 2013 section 3.4). `blocks`: over the 8x8 blocks
// the reprojection listed, one disc pattern (patterns.glsl) per pixel that is new or
// accumulating, merged into the history (temporal.glsl). `refresh`: one workgroup per pixel
// of the refresh tile (refresh.glsl) recomputes it as the mean of every pattern up to the
// rotation limit, the estimator accumulation converges to, blended in along the tile's feather
// ramp (refresh_weight); it runs after `blocks`, which leaves refresh pixels alone.
// @permutation blocks: BLOCKS
// @permutation refresh: REFRESH
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D shadow_depth;
layout(set = 1, binding = 3, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 4, SHADOW_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 6, MOMENTS_FORMAT) uniform image2D moments;

#include "shadow.glsl"

#ifdef REFRESH
#include "refresh.glsl"
layout(local_size_x = REFRESH_THREADS) in;

void main() {
    ivec2 pixel = refresh_pixel();
    uint limit = frame.rotation_limit;
    bool refreshed = !outside_frame(pixel) && imageLoad(state_in, pixel).r == STATE_REFRESH;
    vec4 mine = vec4(0.0); // (sum, 0, 0, sum of squares) of this invocation's patterns
    if (refreshed) {
        vec3 p = texelFetch(g_position, pixel, 0).xyz;
        vec3 n = texelFetch(g_normal, pixel, 0).xyz;
        for (uint j = gl_LocalInvocationIndex; j < limit; j += REFRESH_THREADS) {
            float x = shadow_visibility(p, n, float(j), pixel);
            mine += vec4(x, 0.0, 0.0, x * x);
        }
    }
    vec4 total = refresh_sum(mine);
    if (gl_LocalInvocationIndex != 0u || !refreshed) return;
    vec4 h = imageLoad(history, pixel);
    vec4 m = imageLoad(moments, pixel);
    float w = refresh_blend(refresh_weight(pixel), h.a, total.a / float(limit), m);
    float value = mix(h.r, total.r / float(limit), w);
    imageStore(history, pixel, vec4(clamp(value, 0.0, 1.0), 0.0, 0.0, float(limit)));
    imageStore(moments, pixel, m);
    atomicAdd(counters.computed_pixels, 1u);
    atomicAdd(counters.refresh_evaluations, limit);
    refresh_count_work(limit, shadow_taps());
}
#else
layout(local_size_x = 8, local_size_y = 8) in;

shared uint group_computed;

void main() {
    if (gl_LocalInvocationIndex == 0u) group_computed = 0u;
    barrier();
    ivec2 pixel = block_pixel(gl_LocalInvocationID.xy);
    if (!outside_frame(pixel)) {
        uint state = imageLoad(state_in, pixel).r;
        if (state == STATE_NEW || state == STATE_ACCUMULATING) {
            vec3 p = texelFetch(g_position, pixel, 0).xyz;
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            vec4 h = imageLoad(history, pixel);
            vec4 m = imageLoad(moments, pixel);
            float fresh = shadow_visibility(p, n, h.a, pixel);
            vec2 result = accumulate(h.r, h.a, fresh, m);
            imageStore(history, pixel, vec4(clamp(result.x, 0.0, 1.0), 0.0, 0.0, result.y));
            imageStore(moments, pixel, m);
            atomicAdd(group_computed, 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    if (group_computed > 0u) atomicAdd(counters.computed_pixels, group_computed);
    COUNT_WORK(gather, 64u, group_computed, group_computed > 0u ? shadow_taps() : 0u)
}
#endif
