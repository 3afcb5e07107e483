#version 460
// SVGF's temporal accumulation (Schied et al. section 4.1): this frame's noisy gather merged
// into the colour and into the first and second moments of its luminance that the pixel's
// surface held last frame (previous_texel.glsl: the nearest texel, eq 3's test and the facing
// test), each with weight max(alpha, 1/n) for a history of n samples; where the surface is new
// to the view (or nothing is kept) everything starts over from the sample alone, n = 1. Also
// stores each pixel's reciprocal depth and its screen-space gradient for the spatial passes,
// and counts the pixels that started over.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "svgf.glsl"
#define COUNTERS_BINDING 11
#include "counters.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D prev_position;
layout(set = 1, binding = 3) uniform texture2D prev_normal;
layout(set = 1, binding = 4) uniform texture2D g_motion; // world-space motion since last frame
#include "previous_texel.glsl"
layout(set = 1, binding = 5) uniform texture2D noisy;
layout(set = 1, binding = 6) uniform texture2D color_prev;   // rgb: last frame's colour
layout(set = 1, binding = 7) uniform texture2D moments_prev; // r: samples n, g: E[l], b: E[l^2]
layout(set = 1, binding = 8, rgba32f) uniform writeonly image2D color;
layout(set = 1, binding = 9, rgba32f) uniform writeonly image2D moments;
layout(set = 1, binding = 10, rgba32f) uniform writeonly image2D depth; // z, dz/dx, dz/dy

// Past 1/alpha samples the weights are alpha's: the count only has to stay finite.
const float HISTORY_CAP = 65536.0;

shared uint group_new;
shared uint group_geometry;

// 1 / view depth of pixel q's surface (clip w is the view depth), 0 outside the frame or
// over the background.
float reciprocal_depth(ivec2 q) {
    if (outside_frame(q)) return 0.0;
    vec4 g = texelFetch(g_position, q, 0);
    if (g.w == 0.0) return 0.0;
    float w = (frame.view_proj * vec4(g.xyz, 1.0)).w;
    return w > 0.0 ? 1.0 / w : 0.0;
}

// The one-sided difference of smaller magnitude (the other may cross an edge), 0 when neither
// neighbour has geometry.
float gradient(float z, float before, float after) {
    bool b = before > 0.0, a = after > 0.0;
    float db = z - before, da = after - z;
    if (a && b) return abs(da) <= abs(db) ? da : db;
    return a ? da : (b ? db : 0.0);
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        group_new = 0u;
        group_geometry = 0u;
    }
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    float z = reciprocal_depth(pixel);
    if (!outside_frame(pixel) && z == 0.0) {
        imageStore(color, pixel, vec4(0.0));
        imageStore(moments, pixel, vec4(0.0));
        imageStore(depth, pixel, vec4(0.0));
    } else if (z > 0.0) {
        vec3 x = finite_or_zero(texelFetch(noisy, pixel, 0).rgb);
        // At most HISTORY_MAX (temporal.glsl): its square stays finite in fp32.
        float l = clamp(svgf_luminance(x), 0.0, HISTORY_MAX);
        vec2 fresh = vec2(l, l * l);
        ivec2 t = svgf.history_valid != 0u ? previous_texel(pixel) : ivec2(-1);
        vec3 c;
        vec3 m;
        if (t.x >= 0) {
            vec4 mp = texelFetch(moments_prev, t, 0);
            float n = min(mp.r + 1.0, HISTORY_CAP);
            c = mix(texelFetch(color_prev, t, 0).rgb, x, max(svgf.alpha, 1.0 / n));
            m = vec3(n, mix(mp.gb, fresh, max(svgf.alpha_moments, 1.0 / n)));
        } else {
            c = x;
            m = vec3(1.0, fresh);
            atomicAdd(group_new, 1u);
        }
        atomicAdd(group_geometry, 1u);
        imageStore(color, pixel, vec4(c, 1.0));
        imageStore(moments, pixel, vec4(m, 0.0));
        float gx = gradient(z, reciprocal_depth(pixel - ivec2(1, 0)), reciprocal_depth(pixel + ivec2(1, 0)));
        float gy = gradient(z, reciprocal_depth(pixel - ivec2(0, 1)), reciprocal_depth(pixel + ivec2(0, 1)));
        imageStore(depth, pixel, vec4(z, gx, gy, 0.0));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        if (group_new > 0u) atomicAdd(counters.disoccluded_pixels, group_new);
        if (group_geometry > 0u) atomicAdd(counters.computed_pixels, group_geometry);
    }
}
