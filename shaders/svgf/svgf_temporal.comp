#version 460
// SVGF's temporal accumulation (Schied et al. section 4.1): this frame's noisy gather merged
// into the colour and into the first and second moments of its luminance that the pixel's
// surface held last frame, each with weight max(alpha, 1/n) for a history of n samples. The
// history is last frame's nearest texel where it holds the surface (previous_texel.glsl: eq 3's
// test and the facing test), or with `bilinear` the article's tap: the four texels around the
// previous position, each tested and renormalised over those that hold it; where none does,
// the equal mean of those of the 3x3 block around the nearest that do (thin geometry). Where
// nothing holds it (or nothing is kept), the surface is new to the view and everything starts
// over from the sample alone, n = 1. Also stores each pixel's reciprocal depth and its
// screen-space gradient for the spatial passes, and counts the pixels that started over.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
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

// Last frame's colour, and its moments (n, E[l], E[l^2]), read at this pixel's surface;
// false where no texel held the surface.
bool history(ivec2 pixel, out vec3 c, out vec3 m) {
    c = vec3(0.0);
    m = vec3(0.0);
    if (svgf.history_valid == 0u) return false;
    if (svgf.bilinear == SVGF_HISTORY_NEAREST) {
        ivec2 t = previous_texel(pixel);
        if (t.x < 0) return false;
        c = texelFetch(color_prev, t, 0).rgb;
        m = texelFetch(moments_prev, t, 0).rgb;
        return true;
    }
    vec3 p;
    vec2 f;
    if (!previous_position(pixel, p, f)) return false;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    // The 2x2 texels whose centres surround f, and f's bilinear weights among them.
    vec2 corner = f - 0.5;
    ivec2 base = ivec2(floor(corner));
    vec2 a = corner - vec2(base);
    float total = 0.0;
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        float w = (o.x == 1 ? a.x : 1.0 - a.x) * (o.y == 1 ? a.y : 1.0 - a.y);
        if (w > 0.0 && previous_holds(base + o, p, n)) {
            c += w * texelFetch(color_prev, base + o, 0).rgb;
            m += w * texelFetch(moments_prev, base + o, 0).rgb;
            total += w;
        }
    }
    if (total == 0.0) {
        ivec2 t = ivec2(f);
        for (int i = 0; i < 9; ++i) {
            ivec2 q = t + ivec2(i % 3 - 1, i / 3 - 1);
            if (previous_holds(q, p, n)) {
                c += texelFetch(color_prev, q, 0).rgb;
                m += texelFetch(moments_prev, q, 0).rgb;
                total += 1.0;
            }
        }
    }
    // total is a sum of positive weights, each above 0, or nothing was found: no 0/0.
    if (total == 0.0) return false;
    c /= total;
    m /= total;
    // A count of samples, blended between neighbours: the nearest whole count.
    m.x = max(floor(m.x + 0.5), 1.0);
    return true;
}

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
        vec3 c;
        vec3 m;
        vec3 cp;
        vec3 mp;
        if (history(pixel, cp, mp)) {
            float n = min(mp.x + 1.0, HISTORY_CAP);
            c = mix(cp, x, max(svgf.alpha, 1.0 / n));
            m = vec3(n, mix(mp.yz, fresh, max(svgf.alpha_moments, 1.0 / n)));
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
