#version 460
// GTAO with the cache under camera motion (--gtao-moving-denoise): each pixel's fresh pattern
// (ssao_accumulate.comp `split` wrote it to `raw`) is denoised over its 5x5 neighbours that
// estimated one this frame (gtao_denoise.glsl's edge-aware weights) before it enters the
// history, as XeGTAO denoises before its temporal step. A pattern of two slices is noisy, and
// under motion the moving pixels' running means take one per frame: that noise was GTAO's
// flicker along the walkthroughs (docs/results, lavapipe-ao-16-steps-2026-12-07). A still
// camera merges raw patterns (ssao_accumulate.comp `blocks`), so the converged value stays
// each pixel's own mean of every pattern. Dispatched over the same list as `split`.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"
#include "gtao_denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D raw;
layout(set = 1, binding = 3, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 4, AO_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 6, MOMENTS_FORMAT) uniform image2D moments;

// Whether `split` estimated a pattern at `q` this frame (its `raw` holds this frame's value).
bool estimated(ivec2 q) {
    if (outside_frame(q)) return false;
    uint state = imageLoad(state_in, q).r;
    return state == STATE_NEW || state == STATE_ACCUMULATING;
}

void main() {
    ivec2 pixel = block_pixel(gl_LocalInvocationID.xy);
    if (!estimated(pixel)) return;
    vec3 p = texelFetch(g_position, pixel, 0).xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float inv_plane = gtao_denoise_inv_plane(p);
    float sum = 0.0;
    float weights = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (!estimated(q)) continue;
            float v = texelFetch(raw, q, 0).r;
            // A non-finite pattern is left out here, as accumulate() drops it.
            if (!(abs(v) < FLOAT_MAX)) continue;
            float w = gtao_denoise_weight(ivec2(i, j), p, n, inv_plane,
                                          texelFetch(g_position, q, 0).xyz,
                                          texelFetch(g_normal, q, 0).xyz);
            sum += w * v;
            weights += w;
        }
    }
    // Nothing finite around (the centre's own pattern too): the history stays as it is.
    if (!(weights > 0.0)) return;
    vec4 h = imageLoad(history, pixel);
    vec4 m = imageLoad(moments, pixel);
    vec2 result = accumulate(h.r, h.a, sum / weights, m);
    imageStore(history, pixel, vec4(clamp(result.x, 0.0, 1.0), 0.0, 0.0, result.y));
    imageStore(moments, pixel, m);
}
