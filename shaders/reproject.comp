#version 460
// Reverse reprojection (Lin 2013 eqs 1-3) for one temporal effect: previous texture coordinate
// of every pixel from its world position and last frame's view-projection, disocclusion test
// against the world-position history (and the normal history: FACING_ACCEPT), resampling of the
// effect's history (rgb value, a = estimates) and of its second moment, per-pixel state, and
// the list of work blocks that hold pixels needing work (the effect pass's indirect dispatch).
// Run once per effect with its push constants.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 6
#include "counters.glsl"
#include "effect.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D prev_position; // last frame's G-buffer position
layout(set = 1, binding = 3) uniform texture2D history_prev;
layout(set = 1, binding = 4, rgba32f) uniform writeonly image2D history_cur;
layout(set = 1, binding = 5, r32ui) uniform writeonly uimage2D state_out;
layout(set = 1, binding = 7) uniform texture2D moments_prev;
layout(set = 1, binding = 8, rgba32f) uniform writeonly image2D moments_cur;
layout(set = 1, binding = 9) uniform texture2D prev_normal;    // last frame's G-buffer normal

// Beyond eq 3: a history texel must also face the pixel's way, within 60 degrees. The back of
// a thin wall (or of any two-sided sheet) has the front's position, and a camera passing
// through it would otherwise hand the unlit back's history to the lit front; a crease's other
// face (90 degrees) is another surface too. Curved surfaces turn far less between neighbouring
// texels at any useful resolution.
const float FACING_ACCEPT = 0.5;

shared uint quadrant_needs_work[4];
shared uint group_disoccluded;

bool tap_valid(ivec2 t, vec3 p, vec3 n, float eps) {
    if (outside_frame(t)) return false;
    vec4 h = texelFetch(prev_position, t, 0);
    return h.w != 0.0 && distance(h.xyz, p) <= eps && // eq 3
           dot(texelFetch(prev_normal, t, 0).xyz, n) >= FACING_ACCEPT;
}

// History at the reprojected point: bilinear over the four taps around it when all hold this
// surface, the nearest texel otherwise; the moments (mean squared luminance, pending gate
// crossing, estimates in the mean: the smallest tap's) with the same weights. A static camera (decided on the CPU) reuses the
// texel itself: eq 1's rounding noise would otherwise blend neighbours into a converged value
// every frame, and that noise grows with the coordinates' distance from the origin.
vec4 resample(vec2 f, ivec2 nearest, vec3 p, vec3 n, float eps, out vec4 moments) {
    vec2 g = f - 0.5;
    ivec2 base = ivec2(floor(g)); // f is clamped to [-1, size + 1]: defined conversion
    vec2 w = g - vec2(base);
    bool all_valid = frame.camera_static == 0u;
    for (int k = 0; k < 4 && all_valid; ++k)
        all_valid = tap_valid(base + ivec2(k & 1, k >> 1), p, n, eps);
    if (!all_valid) {
        moments = texelFetch(moments_prev, nearest, 0);
        return texelFetch(history_prev, nearest, 0);
    }
    vec4 m00 = texelFetch(moments_prev, base, 0);
    vec4 m10 = texelFetch(moments_prev, base + ivec2(1, 0), 0);
    vec4 m01 = texelFetch(moments_prev, base + ivec2(0, 1), 0);
    vec4 m11 = texelFetch(moments_prev, base + ivec2(1, 1), 0);
    moments = mix(mix(m00, m10, w.x), mix(m01, m11, w.x), w.y);
    moments.z = min(min(m00.z, m10.z), min(m01.z, m11.z));
    vec4 h00 = texelFetch(history_prev, base, 0);
    vec4 h10 = texelFetch(history_prev, base + ivec2(1, 0), 0);
    vec4 h01 = texelFetch(history_prev, base + ivec2(0, 1), 0);
    vec4 h11 = texelFetch(history_prev, base + ivec2(1, 1), 0);
    vec4 h = mix(mix(h00, h10, w.x), mix(h01, h11, w.x), w.y);
    // A blend holds no more estimates than its weakest tap.
    h.a = min(min(h00.a, h10.a), min(h01.a, h11.a));
    return h;
}

void main() {
    if (gl_LocalInvocationIndex < 4u) quadrant_needs_work[gl_LocalInvocationIndex] = 0u;
    if (gl_LocalInvocationIndex == 0u) group_disoccluded = 0u;
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint state = STATE_BACKGROUND;
    if (!outside_frame(pixel)) {
        vec4 history = vec4(0.0);
        vec4 moments = vec4(0.0);
        vec4 position = texelFetch(g_position, pixel, 0);
        if (position.w != 0.0) {
            vec3 p = position.xyz;
            state = STATE_NEW;
            if (effect.history_valid != 0u) {
                vec4 clip = frame.prev_view_proj * vec4(p, 1.0); // eq 1
                if (clip.w > 0.0) {
                    vec2 f = (clip.xy / clip.w * 0.5 + 0.5) * vec2(frame.size);
                    // Unmoved camera: the pixel is its own previous position.
                    if (frame.camera_static != 0u) f = vec2(pixel) + 0.5;
                    ivec2 nearest = texel_of(f, vec2(frame.size));
                    f = clamp(f, vec2(-1.0), vec2(frame.size) + 1.0);
                    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
                    float eps = disocclusion_epsilon(p, n);
                    if (tap_valid(nearest, p, n, eps)) { // eqs 2-3 on the nearest texel
                        history = resample(f, nearest, p, n, eps, moments);
                        state = history.a >= float(frame.rotation_limit) ? STATE_CONVERGED : STATE_ACCUMULATING;
                    }
                }
            }
            if (state == STATE_NEW) {
                history = vec4(0.0);
                moments = vec4(0.0);
                atomicAdd(group_disoccluded, 1u);
            }
            if (in_refresh_tile(pixel)) state = STATE_REFRESH;
        }
        imageStore(history_cur, pixel, history);
        imageStore(moments_cur, pixel, moments);
        imageStore(state_out, pixel, uvec4(state));
        if (state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH) {
            uvec2 q = gl_LocalInvocationID.xy / 8u;
            atomicOr(quadrant_needs_work[q.y * 2u + q.x], 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        if (group_disoccluded > 0u) atomicAdd(counters.disoccluded_pixels, group_disoccluded);
        uvec2 group = gl_WorkGroupID.xy;
        if (effect.block_shift == 4u) { // 16x16 blocks: the whole group
            uint any_work = quadrant_needs_work[0] | quadrant_needs_work[1] |
                            quadrant_needs_work[2] | quadrant_needs_work[3];
            if (any_work != 0u) {
                uint slot = atomicAdd(counters.dispatch_x, 1u);
                counters.data[slot] = group.x | (group.y << 16);
            }
        } else { // 8x8 blocks: each quadrant on its own
            for (uint k = 0u; k < 4u; ++k) {
                if (quadrant_needs_work[k] == 0u) continue;
                uvec2 b = group * 2u + uvec2(k & 1u, k >> 1);
                uint slot = atomicAdd(counters.dispatch_x, 1u);
                counters.data[slot] = b.x | (b.y << 16);
            }
        }
    }
}
