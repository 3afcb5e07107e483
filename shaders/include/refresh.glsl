// The refresh tile spread over threads: one workgroup of REFRESH_THREADS invocations per
// refreshed pixel, each invocation evaluating every REFRESH_THREADS-th pattern, the sums
// reduced in shared memory. A pixel's full set of patterns then costs one pattern's time on
// enough threads, instead of one invocation looping over them all while the rest of the GPU
// waits (the tile is a few hundred pixels at most: see temporal::budget_tile).
// The including shader declares `layout(local_size_x = REFRESH_THREADS) in;`.
#ifndef REFRESH_GLSL
#define REFRESH_GLSL

#include "effect.glsl"

// REFRESH_THREADS: shared_constants.glsl (config.rs validates the per-thread loop with it).
#include "shared_constants.glsl"

shared vec4 refresh_partial[REFRESH_THREADS];

// The pixel of this workgroup: the tile's pixels in rows (the dispatch has one group each).
ivec2 refresh_pixel() {
    return refresh_tile_pixel(gl_WorkGroupID.x);
}

// Sum of `mine` over the workgroup (every invocation must call it: it holds barriers).
vec4 refresh_sum(vec4 mine) {
    uint t = gl_LocalInvocationIndex;
    refresh_partial[t] = mine;
    barrier();
    for (uint half_count = REFRESH_THREADS / 2u; half_count > 0u; half_count >>= 1u) {
        if (t < half_count) refresh_partial[t] += refresh_partial[t + half_count];
        barrier();
    }
    return refresh_partial[0];
}

// The refresh workgroup's work counters (one invocation calls it): REFRESH_THREADS lanes
// launched, the first `limit` of them evaluating ceil(limit / REFRESH_THREADS) patterns of
// `taps` evaluations each. Needs counters.glsl.
void refresh_count_work(uint limit, uint taps) {
    uint busy = min(limit, REFRESH_THREADS);
    uint per_lane = (limit + REFRESH_THREADS - 1u) / REFRESH_THREADS;
    COUNT_WORK(refresh, REFRESH_THREADS, busy, per_lane * taps)
}

#endif // REFRESH_GLSL
