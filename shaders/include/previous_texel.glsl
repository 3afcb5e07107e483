// Reverse reprojection (Lin 2013 eqs 1-3) for the per-frame filters that keep a history of
// their own (CCIPCA's bases, SVGF's moments): where a pixel's surface was last frame, and
// whether a texel of last frame held it (eq 3's test, and it faces the same way). The includer
// declares the textures g_position, g_normal, prev_position, prev_normal and g_motion.
#ifndef PREVIOUS_TEXEL_GLSL
#define PREVIOUS_TEXEL_GLSL

#include "frame.glsl"
#include "temporal.glsl"

// As the reprojection's facing test (shaders/reproject.comp): within 60 degrees.
const float PREVIOUS_FACING_ACCEPT = 0.5;

// Where this pixel's surface was last frame: its world position then (on a moving object, the
// G-buffer's motion taken back) and last frame's continuous pixel coordinates f, texel centres
// at half-integers. False over the background, behind last frame's camera or off its image.
bool previous_position(ivec2 pixel, out vec3 p, out vec2 f) {
    vec4 g = texelFetch(g_position, pixel, 0);
    f = vec2(-1.0);
    p = g.xyz;
    if (g.w == 0.0) return false;
    p -= texelFetch(g_motion, pixel, 0).xyz;
    vec4 c = frame.prev_view_proj * vec4(p, 1.0);
    if (!(c.w > 0.0)) return false;
    f = (c.xy / c.w * 0.5 + 0.5) * vec2(frame.size);
    return all(greaterThanEqual(f, vec2(0.0))) && all(lessThan(f, vec2(frame.size)));
}

// Whether last frame's texel t held the surface at p with normal n: eq 3's distance test and
// the facing test; false off the image.
bool previous_holds(ivec2 t, vec3 p, vec3 n) {
    if (outside_frame(t)) return false;
    vec4 h = texelFetch(prev_position, t, 0);
    return h.w != 0.0 && distance(h.xyz, p) <= disocclusion_epsilon(p, n) &&
           dot(texelFetch(prev_normal, t, 0).xyz, n) >= PREVIOUS_FACING_ACCEPT;
}

// Last frame's texel holding this pixel's surface, or (-1, -1).
ivec2 previous_texel(ivec2 pixel) {
    vec3 p;
    vec2 f;
    if (!previous_position(pixel, p, f)) return ivec2(-1);
    ivec2 t = ivec2(f);
    return previous_holds(t, p, texelFetch(g_normal, pixel, 0).xyz) ? t : ivec2(-1);
}

#endif // PREVIOUS_TEXEL_GLSL
