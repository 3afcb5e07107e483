// Sampling patterns of the accumulated effects (AO, PCF): pure functions of (tap, pattern,
// pixel) with no bindings, so the passes and the test probe (shaders/probes/pattern_offsets.comp)
// evaluate the same code. Over patterns 0, 1, ... every kernel fills its domain evenly for any
// prefix: the temporal cache's average converges to the continuous kernel, not to a few rings
// or rotations. Sequences run in 32-bit integer arithmetic (a uint wraps at 2^32 exactly as
// a fraction wraps at 1), so index n loses no precision however large it grows; float(n) * alpha
// keeps only 24 - log2(n) bits of the fraction.
#ifndef PATTERNS_GLSL
#define PATTERNS_GLSL

#include "common.glsl"

// A 32-bit fixed-point fraction as a float in [0, 1); the top 24 bits convert exactly.
float unorm32(uint x) {
    return float(x >> 8) * (1.0 / 16777216.0);
}

// Golden-ratio Kronecker sequence fract(1/2 + n / phi): the 1D sequence with the smallest
// discrepancy for every prefix (2^32 / phi = 0x9E3779B9).
uint golden_sequence(uint n) {
    return 0x80000000u + n * 0x9E3779B9u;
}

// Van der Corput sequence in base 2 (the radical inverse: n's bits mirrored): every prefix of
// 2^k points is one per 2^-k stratum.
uint van_der_corput(uint n) {
    return bitfieldReverse(n);
}

// Radical inverse of n in base 3: the second Halton dimension.
float radical_inverse3(uint n) {
    float r = 0.0;
    float f = 1.0 / 3.0;
    while (n != 0u) {
        r += f * float(n % 3u);
        n /= 3u;
        f *= 1.0 / 3.0;
    }
    return r;
}

// Pattern j's point in [0, 1)^2: x = van der Corput with its top bit flipped (a digit
// scramble that keeps the strata), y = the golden sequence; pattern 0 is (1/2, 1/2). x drives
// rotations, y radii and range scales. The pair is a hybrid (van der Corput, Kronecker)
// low-discrepancy sequence; x in base 2 interleaves the rotations of the PCF taps (whose
// angles differ by the golden angle) about three times more evenly than the golden sequence.
vec2 pattern_point(uint j) {
    return vec2(unorm32(van_der_corput(j) ^ 0x80000000u), unorm32(golden_sequence(j)));
}

// Lin 2013 eqs 6-8, pattern j: rotation of the `directions` regular directions, a fraction of
// the 2 pi / directions sector between them (so no rotation repeats: 10 degrees x j with 8
// directions revisits 9 angles), and the range scale 1 +- 10% (the thesis scales the range
// "slightly" each frame). Pattern 0: half a sector, scale 1.
vec2 ao_thesis_pattern(uint j, uint directions) {
    vec2 u = pattern_point(j);
    return vec2(TWO_PI * u.x / float(max(directions, 1u)), 1.0 + 0.2 * (u.y - 0.5));
}

// Eq 8, S_i = near (far / near)^(i / (m - 1)) for i = 0 .. m - 1: the first step is `near`,
// the last `far`, as the equation's range [near, far] says (i = 1 .. m would never sample
// near). One step (m = 1) samples near.
float ao_step_px(uint i, uint steps, float near_px, float far_px) {
    return near_px * pow(far_px / near_px, float(i) / float(max(steps, 2u) - 1u));
}

// Mittring's kernel: sample k of `count` in pattern j as a point of the unit ball in the
// frame (tangent, bitangent, view direction). Index n = j count + k runs through a 3D
// low-discrepancy sequence: cos(theta) from base 2, r^3 from base 3, azimuth from the golden
// sequence, so over any prefix of patterns the points are uniform in the ball (the direction
// uniform on the sphere, r^3 uniform, the two independent) and each pattern alone is
// stratified in depth. The per-pixel rotation about the view axis comes on top.
vec3 crytek_offset(uint k, uint count, uint j) {
    uint n = j * count + k;
    float z = 1.0 - 2.0 * unorm32(van_der_corput(n));
    float r_xy = sqrt(max(1.0 - z * z, 0.0));
    float phi = TWO_PI * unorm32(golden_sequence(n));
    float r = pow(radical_inverse3(n), 1.0 / 3.0);
    return r * vec3(r_xy * cos(phi), r_xy * sin(phi), z);
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel value in [0, 1) whose 3x3
// neighbourhoods are spread evenly, so per-pixel rotations turn one pattern's banding into
// fine noise. Exact enough for pixel coordinates below 2^12.
float interleaved_gradient_noise(ivec2 pixel) {
    return fract(52.9829189 * fract(dot(vec2(pixel), vec2(0.06711056, 0.00583715))));
}

// PCF disc tap j of `count` in pattern `pattern` at `pixel`, in units of the kernel radius. A
// Vogel spiral (tap j's angle j times the golden angle) whose tap j lies in its own annulus
// sqrt([j, j + 1) / count): the pattern's radial offset moves it across that annulus uniformly
// in area, and the pattern's rotation plus the pixel's turn it around the disc, so over
// patterns the taps fill the disc uniformly (the thesis rotates and scales the pattern each
// frame; a scale of the whole spiral would only ever cover count rings). Pattern 0 is the
// classic spiral sqrt((j + 1/2) / count) for every count, turned by the pixel's noise.
vec2 pcf_disc_offset(uint j, uint count, uint pattern, ivec2 pixel) {
    vec2 u = pattern_point(pattern);
    float rho = sqrt((float(j) + u.y) / float(max(count, 1u)));
    // j times the golden angle as a 32-bit fraction of a turn (2^32 (1 - 1/phi) = 0x61C88647).
    float turns = unorm32(j * 0x61C88647u) + u.x + interleaved_gradient_noise(pixel);
    float phi = TWO_PI * fract(turns);
    return rho * vec2(cos(phi), sin(phi));
}

#endif // PATTERNS_GLSL
