#version 460
// Reverse reprojection (Lin 2013 eqs 1-3): previous texture coordinate of every pixel from its
// world position and last frame's view-projection, disocclusion test against the world-position
// history, resampling of the AO history, per-pixel state, and the list of 8x8 blocks that hold
// pixels needing work (consumed by the SSAO pass's indirect dispatch).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 6
#include "counters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D prev_position; // last frame's G-buffer position
layout(set = 1, binding = 3) uniform texture2D ao_prev;       // r = value, g = estimates
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D ao_cur;
layout(set = 1, binding = 5, r32ui) uniform writeonly uimage2D state_out;

shared uint block_needs_work;
shared uint block_disoccluded;

bool tap_valid(ivec2 t, vec3 p, float eps) {
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(uvec2(t), frame.size.xy))) return false;
    vec4 h = texelFetch(prev_position, t, 0);
    return h.w != 0.0 && distance(h.xyz, p) <= eps; // eq 3
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        block_needs_work = 0u;
        block_disoccluded = 0u;
    }
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(uvec2(pixel), frame.size.xy));
    uint state = STATE_BACKGROUND;
    vec2 ao = vec2(1.0, 0.0);
    if (inside) {
        vec4 position = texelFetch(g_position, pixel, 0);
        if (position.w != 0.0) {
            vec3 p = position.xyz;
            state = STATE_NEW;
            if (frame.temporal.x != 0u) {
                vec4 clip = frame.prev_view_proj * vec4(p, 1.0); // eq 1
                if (clip.w > 0.0) {
                    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
                    vec2 f = uv * vec2(frame.size.xy);
                    ivec2 nearest = ivec2(floor(f));
                    float eps = disocclusion_epsilon(p, texelFetch(g_normal, pixel, 0).xyz);
                    if (tap_valid(nearest, p, eps)) { // eq 2-3 on the nearest texel
                        // Bilinear over the four taps around the sample point when all hold
                        // the same surface; otherwise the nearest texel alone.
                        vec2 g = f - 0.5;
                        ivec2 base = ivec2(floor(g));
                        vec2 w = g - vec2(base);
                        // Sub-1/1000-pixel motion is rounding noise of eq 1 (a static camera):
                        // reuse the texel itself, or fp16 history would drift by blending.
                        bool still = all(lessThan(abs(w - round(w)), vec2(1e-3)));
                        bool all_valid = !still;
                        for (int k = 0; k < 4; ++k)
                            all_valid = all_valid && tap_valid(base + ivec2(k & 1, k >> 1), p, eps);
                        if (all_valid) {
                            vec2 h00 = texelFetch(ao_prev, base, 0).rg;
                            vec2 h10 = texelFetch(ao_prev, base + ivec2(1, 0), 0).rg;
                            vec2 h01 = texelFetch(ao_prev, base + ivec2(0, 1), 0).rg;
                            vec2 h11 = texelFetch(ao_prev, base + ivec2(1, 1), 0).rg;
                            float value = mix(mix(h00.x, h10.x, w.x), mix(h01.x, h11.x, w.x), w.y);
                            // A blend holds no more estimates than its weakest tap.
                            float n = min(min(h00.y, h10.y), min(h01.y, h11.y));
                            ao = vec2(value, n);
                        } else {
                            ao = texelFetch(ao_prev, nearest, 0).rg;
                        }
                        state = ao.y >= float(frame.temporal.w) ? STATE_CONVERGED : STATE_ACCUMULATING;
                    }
                }
            }
            if (state == STATE_NEW) {
                ao = vec2(1.0, 0.0);
                atomicAdd(block_disoccluded, 1u);
            }
            uvec2 tile = frame.temporal.yz;
            if (tile.x != 0xffffffffu && all(greaterThanEqual(uvec2(pixel), tile)) &&
                all(lessThan(uvec2(pixel), tile + 64u))) {
                state = STATE_REFRESH;
            }
        }
        imageStore(ao_cur, pixel, vec4(ao, 0.0, 0.0));
        imageStore(state_out, pixel, uvec4(state));
        if (state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH)
            atomicOr(block_needs_work, 1u);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        if (block_disoccluded > 0u) atomicAdd(counters.disoccluded_pixels, block_disoccluded);
        if (block_needs_work != 0u) {
            uint slot = atomicAdd(counters.dispatch_x, 1u);
            counters.blocks[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
        }
    }
}
