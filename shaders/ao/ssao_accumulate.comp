#version 460
// SSAO with temporal reuse. `blocks`: dispatched indirectly over the 8x8 blocks the
// reprojection listed; evaluates one rotated pattern per pixel that is new or accumulating and
// merges it into the history (temporal.glsl: the gated running mean, eqs 4-5, EMA or capped
// mean). Converged pixels are left alone. `refresh`: one workgroup per pixel of the refresh
// tile (refresh.glsl, each lane a range of one pattern's taps) recomputes it from scratch as
// the mean of every pattern up to the rotation limit, the estimator accumulation converges to, blended in along the tile's feather
// ramp (refresh_weight); it runs after `blocks`, which leaves refresh pixels alone.
// `split`: `blocks` under camera motion with GTAO's per-pattern denoise (--gtao-moving-denoise):
// writes each fresh pattern to `raw` and leaves the merge to gtao_moving.comp.
// @permutation blocks: BLOCKS
// @permutation split: BLOCKS SPLIT
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
layout(set = 1, binding = 2) uniform texture2D random_vectors;
// ao_position_chain.comp's point-sampled levels 1-3 of g_position (far taps).
layout(set = 1, binding = 7) uniform texture2D g_position_1;
layout(set = 1, binding = 8) uniform texture2D g_position_2;
layout(set = 1, binding = 9) uniform texture2D g_position_3;
layout(set = 1, binding = 3, STATE_FORMAT) uniform readonly uimage2D state_in;
#ifdef SPLIT
layout(set = 1, binding = 4, AO_HISTORY_FORMAT) uniform readonly image2D history;
// This frame's fresh visibility of each listed pixel, for gtao_moving.comp.
layout(set = 1, binding = 10, rgba16f) uniform writeonly image2D raw;
#else
layout(set = 1, binding = 4, AO_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 6, MOMENTS_FORMAT) uniform image2D moments;
#endif

#include "ao.glsl"

#ifdef REFRESH
#include "refresh.glsl"
layout(local_size_x = REFRESH_THREADS) in;

// One pattern's taps split into `slices` consecutive ranges, one lane each: 36 patterns on 64
// lanes left 28 idle; 36 x 16 ranges of 2 taps fill 9 rounds of 64.
shared float slice_sum[REFRESH_THREADS];

// Ranges per pattern: the power of two (at most the taps, and a divisor of the workgroup)
// that keeps the most lane-rounds busy; the fewest such ranges (fewer partial sums).
uint slices_per_pattern(uint limit, uint taps) {
    uint best = 1u;
    uint best_busy = 0u; // busy lane-rounds per 1024 launched
    for (uint s = 1u; s <= REFRESH_THREADS && s <= taps; s *= 2u) {
        uint units = limit * s;
        uint rounds = (units + REFRESH_THREADS - 1u) / REFRESH_THREADS;
        uint busy = units * 1024u / (rounds * REFRESH_THREADS);
        if (busy > best_busy) {
            best = s;
            best_busy = busy;
        }
    }
    return best;
}

void main() {
    ivec2 pixel = refresh_pixel();
    uint limit = frame.rotation_limit;
    uint taps = ao_taps();
    // One pixel per workgroup: uniform, so the barriers below are in uniform control flow.
    bool refreshed = !outside_frame(pixel) && imageLoad(state_in, pixel).r == STATE_REFRESH;
    uint slices = slices_per_pattern(limit, taps);
    uint units = limit * slices;
    uint rounds = (units + REFRESH_THREADS - 1u) / REFRESH_THREADS;
    uint t = gl_LocalInvocationIndex;
    vec3 p = vec3(0.0);
    vec3 n = vec3(0.0);
    if (refreshed) {
        p = texelFetch(g_position, pixel, 0).xyz;
        n = texelFetch(g_normal, pixel, 0).xyz;
    }
    vec4 mine = vec4(0.0); // (sum, 0, 0, sum of squares) of the patterns this lane closes
    for (uint r = 0u; r < rounds; ++r) {
        uint u = r * REFRESH_THREADS + t;
        uint pattern = u / slices;
        uint slice = u % slices;
        bool live = refreshed && pattern < limit;
        float part = 0.0;
        if (live)
            part = ao_taps_sum(g_position, g_position_1, g_position_2, g_position_3, g_normal, random_vectors, pixel, p, n, pattern, slice * taps / slices,
                               (slice + 1u) * taps / slices);
        slice_sum[t] = part;
        barrier();
        // REFRESH_THREADS is a multiple of `slices`: a pattern's ranges sit in one round.
        if (live && slice == 0u) {
            float occluded = 0.0;
            for (uint k = 0u; k < slices; ++k) occluded += slice_sum[t + k];
            float x = 1.0 - occluded / float(taps);
            mine += vec4(x, 0.0, 0.0, x * x);
        }
        barrier();
    }
    vec4 total = refresh_sum(mine);
    if (t != 0u || !refreshed) return;
    vec4 h = imageLoad(history, pixel);
    vec4 m = imageLoad(moments, pixel);
    float w = refresh_blend(refresh_weight(pixel), h.a, total.a / float(limit), m);
    float value = mix(h.r, total.r / float(limit), w);
    imageStore(history, pixel, vec4(clamp(value, 0.0, 1.0), 0.0, 0.0, float(limit)));
    imageStore(moments, pixel, m);
    atomicAdd(counters.computed_pixels, 1u);
    atomicAdd(counters.refresh_evaluations, limit);
    COUNT_WORK(refresh, rounds * REFRESH_THREADS, units, rounds * ((taps + slices - 1u) / slices))
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
            // Each pixel walks through patterns 0, 1, ... in the order it accumulates them.
            float fresh = 1.0 - ao_estimate(g_position, g_position_1, g_position_2, g_position_3, g_normal, random_vectors, pixel, p, n, h.a, 1u);
#ifdef SPLIT
            imageStore(raw, pixel, vec4(fresh, 0.0, 0.0, 1.0));
#else
            vec4 m = imageLoad(moments, pixel);
            vec2 result = accumulate(h.r, h.a, fresh, m);
            imageStore(history, pixel, vec4(clamp(result.x, 0.0, 1.0), 0.0, 0.0, result.y));
            imageStore(moments, pixel, m);
#endif
            atomicAdd(group_computed, 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    if (group_computed > 0u) atomicAdd(counters.computed_pixels, group_computed);
    COUNT_WORK(gather, 64u, group_computed, group_computed > 0u ? ao_taps() : 0u)
}
#endif
