// SVGF (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering"): its push constants and
// the edge-stopping weight its spatial passes share. Every image is the indirect light's
// irradiance, before the albedo: already the article's demodulated illumination.
#ifndef SVGF_GLSL
#define SVGF_GLSL

#include "frame.glsl"

layout(push_constant) uniform Svgf {
    uint history_valid;    // 0: every pixel starts over (first frame, resize, --reuse off)
    float alpha;           // the colour's smallest weight of a new sample (the article: 0.2)
    float alpha_moments;   // the luminance moments' (0.2)
    uint bilinear;         // SVGF_HISTORY_* (shared_constants.glsl): the bilinear tap or the nearest texel
    uint step;             // a-trous: pixels between taps, 2^iteration
    float sigma_luminance; // sigma_l, in standard deviations (4)
    float sigma_normal;    // sigma_n, the exponent of max(0, n . n_q) (128)
    float sigma_depth;     // sigma_z, in depth changes the gradient predicts (1)
} svgf;

// Floors of the depth and luminance scales, relative to the centre's own value so that they
// hold at any scene scale and radiance range: reciprocal depths within 0.1% of the centre's,
// or luminances within 0.1% of its luminance, never make an edge by themselves (a surface
// facing the camera has no depth gradient; a converged pixel has no variance), and neither
// scale is ever 0.
const float DEPTH_FLOOR = 1e-3;
const float LUMINANCE_FLOOR = 1e-3;
// Below any luminance: a black centre with no variance still divides by a positive number.
const float LUMINANCE_TINY = 1e-30;

float svgf_luminance(vec3 c) {
    return dot(c, LUMA);
}

// The article's edge-stopping weight of tap q for centre p (its eqs 3-5): depths z (the
// reciprocal of the view depth, linear in screen space on a plane) against the change the
// centre's gradient predicts over `offset` pixels, normals, and luminances against `phi_l` (0
// or less: no luminance term, the spatial variance estimate's weight).
float edge_weight(vec3 z_p, float l_p, float phi_l, vec3 n_p, float z_q, float l_q, vec3 n_q, vec2 offset) {
    float phi_z = svgf.sigma_depth * abs(dot(z_p.yz, offset)) + DEPTH_FLOOR * z_p.x;
    // pow(0, 0) is undefined: an exponent of 0 turns the normal term off.
    float w_n = svgf.sigma_normal > 0.0 ? pow(max(dot(n_p, n_q), 0.0), svgf.sigma_normal) : 1.0;
    float e = abs(z_p.x - z_q) / phi_z;
    if (phi_l > 0.0) e += abs(l_p - l_q) / phi_l;
    return w_n * exp(-e);
}

#endif // SVGF_GLSL
