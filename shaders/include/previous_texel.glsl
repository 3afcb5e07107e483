// Nearest-texel reverse reprojection (Lin 2013 eqs 1-3) for the per-frame filters that keep a
// history of their own (CCIPCA's bases, SVGF's moments): last frame's texel holding a pixel's
// surface, kept where eq 3's test holds and it faces the same way. The includer declares the
// textures g_position, g_normal, prev_position, prev_normal and g_motion.
#ifndef PREVIOUS_TEXEL_GLSL
#define PREVIOUS_TEXEL_GLSL

#include "frame.glsl"
#include "temporal.glsl"

// As the reprojection's facing test (shaders/reproject.comp): within 60 degrees.
const float PREVIOUS_FACING_ACCEPT = 0.5;

// Last frame's texel holding this pixel's surface, or (-1, -1); on a moving object, where its
// point was last frame (the G-buffer's motion).
ivec2 previous_texel(ivec2 pixel) {
    vec4 g = texelFetch(g_position, pixel, 0);
    if (g.w == 0.0) return ivec2(-1);
    g.xyz -= texelFetch(g_motion, pixel, 0).xyz;
    vec4 c = frame.prev_view_proj * vec4(g.xyz, 1.0);
    if (!(c.w > 0.0)) return ivec2(-1);
    vec2 f = (c.xy / c.w * 0.5 + 0.5) * vec2(frame.size);
    if (!(all(greaterThanEqual(f, vec2(0.0))) && all(lessThan(f, vec2(frame.size))))) return ivec2(-1);
    ivec2 t = ivec2(f);
    vec4 h = texelFetch(prev_position, t, 0);
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    bool same = h.w != 0.0 && distance(h.xyz, g.xyz) <= disocclusion_epsilon(g.xyz, n) &&
                dot(texelFetch(prev_normal, t, 0).xyz, n) >= PREVIOUS_FACING_ACCEPT;
    return same ? t : ivec2(-1);
}

#endif // PREVIOUS_TEXEL_GLSL
