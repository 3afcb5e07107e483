// Halton sampling of the hemisphere after Szentandrasi (section 4.2, eqs 5-8), for the
// effects that estimate occlusion from hemisphere samples. Pure functions, no bindings (the probe
// shaders/probes/pattern_offsets.comp evaluates them for the tests).
#ifndef HALTON_GLSL
#define HALTON_GLSL

#include "common.glsl"
#include "patterns.glsl"

// The direction's two dimensions use bases 2 and 5: relatively prime (eq 7), the paper's
// Figure 4. Eq 8 with k = 1 gives each base's period b, so the pair repeats its strata every
// lcm(2, 5) = 10 indices: any whole number of periods (10, 20, ..., 50 samples) is spread as
// evenly as the sequence itself, which is what lets the sample count vary per pixel.
const uint HALTON_BASE_U = 2u;
const uint HALTON_BASE_V = 5u;
const uint HALTON_PERIOD = 10u;

// Eq 6: the digits of n in base `base` mirrored about the point. Exact digits, accumulated
// in float: within 2^-23 relative of the definition for any n.
float radical_inverse(uint n, uint base) {
    float inv = 1.0 / float(base);
    float f = inv;
    float r = 0.0;
    while (n != 0u) {
        r += f * float(n % base);
        n /= base;
        f *= inv;
    }
    return r;
}

// Per-pixel Cranley-Patterson shift of the Halton points: every pixel sees the same evenly
// spread set, moved by its own offset modulo 1, so neighbouring pixels sample different
// directions (fine noise the bilateral filter removes) without losing the stratification.
// Interleaved gradient noise spreads the offsets of each 3x3 neighbourhood evenly; the second
// coordinate reads it at a transposed, shifted pixel so the two are not correlated.
vec2 halton_pixel_shift(ivec2 pixel) {
    return vec2(interleaved_gradient_noise(pixel), interleaved_gradient_noise(pixel.yx + ivec2(37, 11)));
}

// An orthonormal basis (t, b, n) around the unit vector n (Duff et al. 2017, branchless and
// continuous except at n.z = -1 exactly, where it still returns a valid basis).
void basis_around(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Halton point i after the pixel's shift, in [0, 1)^2.
vec2 halton_point(uint i, vec2 shift) {
    return fract(vec2(radical_inverse(i, HALTON_BASE_U), radical_inverse(i, HALTON_BASE_V)) + shift);
}

// Sample i's unit direction in the hemisphere around n, uniform in solid angle (cos theta
// uniform in [0, 1)), so each sample stands for 2 pi / K steradians (eq 2's delta omega).
vec3 halton_hemisphere(vec2 u, vec3 n) {
    float cos_t = u.x;
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    float phi = TWO_PI * u.y;
    vec3 t, b;
    basis_around(n, t, b);
    return sin_t * (cos(phi) * t + sin(phi) * b) + cos_t * n;
}

// Sample i's step along its direction, r in [0, r_max) uniform ("a random step", section
// 3.2.1): the golden sequence shifted per pixel, a third dimension independent of the two
// Halton bases, so it does not change their period.
float halton_step(uint i, float pixel_offset) {
    return fract(unorm32(golden_sequence(i)) + pixel_offset);
}

#endif // HALTON_GLSL
