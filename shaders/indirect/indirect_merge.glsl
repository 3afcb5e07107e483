// Requires `history` (INDIRECT_HISTORY_FORMAT) and `moments` (MOMENTS_FORMAT) storage images declared by the including
// shader.
#ifndef INDIRECT_MERGE_GLSL
#define INDIRECT_MERGE_GLSL

#include "temporal.glsl"

// Merge a fresh estimate (rgb, a = mean squared luminance of its patterns) into the history at
// `pixel` (rgb value, a = estimates) and its second moment.
void merge(ivec2 pixel, vec4 h, vec4 fresh, bool refresh) {
    // A non-finite estimate (a degenerate VPL) is dropped: `clamp` below would keep a NaN.
    if (!all_finite(fresh.rgb) || !(abs(fresh.a) < FLOAT_MAX)) return;
    vec4 m = imageLoad(moments, pixel);
    vec4 result;
    if (refresh) {
        float w = refresh_blend(refresh_weight(pixel), h.a, fresh.a, m);
        result = vec4(mix(h.rgb, fresh.rgb, w), float(frame.rotation_limit));
    } else {
        result = accumulate3(h.rgb, h.a, fresh.rgb, m);
    }
    // Non-negative and bounded (the estimate is finite here).
    imageStore(history, pixel, vec4(clamp(result.rgb, vec3(0.0), vec3(HISTORY_MAX)), result.a));
    m.x = clamp(m.x, 0.0, HISTORY_MAX * HISTORY_MAX);
    imageStore(moments, pixel, m);
}

#endif // INDIRECT_MERGE_GLSL
