#version 460
// SSDO with the reverse reprojection cache (beyond the paper, `--reuse on`): one-step SSDO (or
// `--ssdo ssao`) accumulated like the thesis's effects. A pattern is K Halton points: pattern j
// takes indices jK .. jK + K - 1 (whole periods when K is a multiple of 10), so the patterns a
// pixel accumulates are the first (n + 1) K points of one sequence, each pattern evenly spread.
// The modulation factor (SSAO: the unoccluded fraction) drives the merge (temporal.glsl: the
// gated running mean, eqs 4-5, EMA or capped mean) and its running mean lives in the moments'
// w; the bounce, undarkened, is merged into the history's rgb with the same weight (history a =
// patterns), and `resolve` darkens the mean bounce by the mean factor: E[bounce] E[factor], what
// one pass with every pattern's samples computes. Darkening each pattern by its own factor
// converged to E[bounce x factor], low by their covariance (occluded samples raise one and
// lower the other).
// `blocks`: over the 8x8 blocks the reprojection listed, one pattern per new or accumulating
// pixel. `refresh`: one workgroup per pixel of the refresh tile recomputes it as the mean of
// every pattern up to the rotation limit. `resolve`: every pixel's (bounce, factor) into the
// image the bilateral filter and the composite read (SSAO: the fraction in every channel).
// @permutation blocks: BLOCKS
// @permutation refresh: REFRESH
// @permutation blocks_ssao: BLOCKS SSAO
// @permutation refresh_ssao: REFRESH SSAO
// @permutation resolve: RESOLVE
// @permutation resolve_ssao: RESOLVE SSAO
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "ssdo_params.glsl"

layout(set = 1, binding = 0) uniform texture2D g_position;

#ifdef RESOLVE
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 1) uniform texture2D history;
layout(set = 1, binding = 2) uniform texture2D moments;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D ssdo_out;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 result = vec4(0.0, 0.0, 0.0, 1.0);
    if (texelFetch(g_position, pixel, 0).w != 0.0) {
        float m = texelFetch(moments, pixel, 0).w;
#ifdef SSAO
        result = vec4(m);
#else
        result = vec4(texelFetch(history, pixel, 0).rgb * m, m);
#endif
    }
    imageStore(ssdo_out, pixel, result);
}
#else
#include "temporal.glsl"
#define COUNTERS_BINDING 6
#include "counters.glsl"
#include "effect.glsl"

layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D g_albedo;
// The direct effect's outgoing radiance (read when ssdo.direct_enabled).
layout(set = 1, binding = 3) uniform texture2D direct_light;
layout(set = 1, binding = 4, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 5, SSDO_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 7, MOMENTS_FORMAT) uniform image2D moments;
// The pre-pass's samples per block (read when ssdo.threshold_count > 0).
layout(set = 1, binding = 8) uniform utexture2D block_samples;

// Senders lit as the frame is without SSDO (the one-step form): direct light + ambient.
vec3 sender_radiance(ivec2 q) {
    vec3 l = frame.ambient * texelFetch(g_albedo, q, 0).rgb;
    if (ssdo.direct_enabled != 0u) l += texelFetch(direct_light, q, 0).rgb;
    return l;
}

#include "ssdo.glsl"

uint sample_count(ivec2 pixel) {
    if (ssdo.threshold_count > 0u)
        return texelFetch(block_samples, pixel / int(ssdo.prepass_scale), 0).r;
    return ssdo.samples;
}

// Pattern `pattern`'s estimate: (bounce, modulation factor), the bounce not yet darkened by
// the factor (`resolve` does it with both means); SSAO: (0, unoccluded fraction). Clamped so
// histories stay finite.
vec4 estimate(ivec2 pixel, vec3 p, vec3 n, uint pattern, uint count) {
    uint first = pattern * count;
#ifdef SSAO
    return vec4(0.0, 0.0, 0.0, ssao_pixel(g_position, g_normal, pixel, p, n, first, count));
#else
    vec4 e = ssdo_pixel(g_position, g_normal, pixel, p, n, first, count, count * frame.rotation_limit, true);
    vec3 bounce = clamp(e.rgb, vec3(0.0), vec3(HISTORY_MAX));
    return vec4(bounce, clamp(e.a, 0.0, 1.0));
#endif
}

#ifdef REFRESH
#include "refresh.glsl"
layout(local_size_x = REFRESH_THREADS) in;

void main() {
    ivec2 pixel = refresh_pixel();
    uint limit = frame.rotation_limit;
    bool refreshed = !outside_frame(pixel) && imageLoad(state_in, pixel).r == STATE_REFRESH;
    vec4 bounce = vec4(0.0); // sum of this invocation's patterns' bounce
    vec4 factor = vec4(0.0); // (sum, 0, 0, sum of squares) of their modulation factors
    uint count = 0u;
    if (refreshed) {
        vec3 p = texelFetch(g_position, pixel, 0).xyz;
        vec3 n = texelFetch(g_normal, pixel, 0).xyz;
        count = sample_count(pixel);
        for (uint j = gl_LocalInvocationIndex; j < limit; j += REFRESH_THREADS) {
            vec4 e = estimate(pixel, p, n, j, count);
            bounce += vec4(e.rgb, 0.0);
            factor += vec4(e.a, 0.0, 0.0, e.a * e.a);
        }
    }
    vec4 bounce_total = refresh_sum(bounce);
    // Every invocation has read the first sum before the shared array is reused.
    barrier();
    vec4 factor_total = refresh_sum(factor);
    if (gl_LocalInvocationIndex != 0u || !refreshed) return;
    vec4 h = imageLoad(history, pixel);
    vec4 m = imageLoad(moments, pixel);
    float old_factor = m.w;
    float inv = 1.0 / float(limit);
    float w = refresh_blend(refresh_weight(pixel), h.a, factor_total.w * inv, m);
    m.w = mix(old_factor, factor_total.x * inv, w);
    imageStore(history, pixel, vec4(mix(h.rgb, bounce_total.rgb * inv, w), float(limit)));
    imageStore(moments, pixel, m);
    atomicAdd(counters.computed_pixels, 1u);
    atomicAdd(counters.refresh_evaluations, limit);
    atomicAdd(counters.samples, limit * count);
    refresh_count_work(limit, count);
}
#else
layout(local_size_x = 8, local_size_y = 8) in;

shared uint group_computed;
shared uint group_samples;
shared uint group_serial;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        group_computed = 0u;
        group_samples = 0u;
        group_serial = 0u;
    }
    barrier();
    ivec2 pixel = block_pixel(gl_LocalInvocationID.xy);
    if (!outside_frame(pixel)) {
        uint state = imageLoad(state_in, pixel).r;
        if (state == STATE_NEW || state == STATE_ACCUMULATING) {
            vec3 p = texelFetch(g_position, pixel, 0).xyz;
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            uint count = sample_count(pixel);
            vec4 h = imageLoad(history, pixel);
            vec4 m = imageLoad(moments, pixel);
            // Each pixel walks through patterns 0, 1, ... in the order it accumulates them.
            vec4 fresh = estimate(pixel, p, n, uint(h.a), count);
            float old_factor = m.w;
            float w = merge_weight(old_factor, h.a, fresh.a, m);
            m.w = mix(old_factor, fresh.a, w);
            imageStore(history, pixel, vec4(mix(h.rgb, fresh.rgb, w), h.a + 1.0));
            imageStore(moments, pixel, m);
            atomicAdd(group_computed, 1u);
            atomicAdd(group_samples, count);
            atomicMax(group_serial, count);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex != 0u) return;
    if (group_computed > 0u) {
        atomicAdd(counters.computed_pixels, group_computed);
        atomicAdd(counters.samples, group_samples);
    }
    COUNT_WORK(gather, 64u, group_computed, group_serial)
}
#endif
#endif
