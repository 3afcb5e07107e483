// Screen-space visibility of a point of the hemisphere (Szentandrasi section 3.2.1, Ritschel
// et al. 2009), shared by the hemisphere-sampling effects. The G-buffer it reads is a parameter.
#ifndef HEMISPHERE_GLSL
#define HEMISPHERE_GLSL

#include "frame.glsl"
#include "halton.glsl"

// What the G-buffer shows where the sample point s projects.
struct HemisphereTap {
    bool occluded;  // s lies behind the visible surface there: an occluder in its direction
    bool on_screen; // s projects inside the image onto geometry (q and its normal are valid)
    vec3 q;         // the visible surface point there (a bounce's sender)
    vec3 q_normal;
    ivec2 q_pixel;
};

// s is occluded when it lies below the tangent plane of the visible surface at its pixel
// (by more than 1e-4 of its view depth: fp32 noise) and that surface is in front of it by
// less than r_max. The tangent-plane test is exact for planes at any slant, where a plain
// depth comparison needs a bias that grows at grazing angles; the range test keeps a surface
// far in front of the hemisphere (another object) from darkening p.
HemisphereTap hemisphere_tap(texture2D position, texture2D normals, vec3 s, float r_max) {
    HemisphereTap tap;
    tap.occluded = false;
    tap.on_screen = false;
    tap.q = s;
    tap.q_normal = vec3(0.0);
    tap.q_pixel = ivec2(-1);
    vec4 clip = frame.view_proj * vec4(s, 1.0);
    if (!(clip.w > 0.0)) return tap;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    ivec2 q_pixel = texel_of(uv * vec2(frame.size), vec2(frame.size));
    if (outside_frame(q_pixel)) return tap;
    vec4 q = texelFetch(position, q_pixel, 0);
    if (q.w == 0.0) return tap;
    vec3 qn = texelFetch(normals, q_pixel, 0).xyz;
    float gap = clip.w - (frame.view_proj * vec4(q.xyz, 1.0)).w;
    tap.on_screen = true;
    tap.q = q.xyz;
    tap.q_normal = qn;
    tap.q_pixel = q_pixel;
    tap.occluded = dot(s - q.xyz, qn) < -1e-4 * clip.w && gap < r_max;
    return tap;
}

// Hemisphere sample i of pixel `pixel` around (p, n): the point p + r omega, with omega from
// the shifted Halton point and r from the shifted golden sequence. Returns omega in xyz and r.
vec4 hemisphere_sample(uint i, ivec2 pixel, vec3 n, float r_max) {
    vec2 shift = halton_pixel_shift(pixel);
    vec3 omega = halton_hemisphere(halton_point(i, shift), n);
    return vec4(omega, r_max * halton_step(i, fract(shift.x + shift.y)));
}

#endif // HEMISPHERE_GLSL
