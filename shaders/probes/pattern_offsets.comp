#version 460
// Test probe, not a pass: writes the sampling offsets the AO and PCF patterns use, computed by
// the very functions the passes call (include/patterns.glsl, include/halton.glsl), so tests
// can check the
// distribution of the offsets the shaders really use. Invocation (x, y): tap x % count of
// pattern first_pattern + x / count, at pixel (y, 3 y) (the PCF's per-pixel rotation).
#extension GL_GOOGLE_include_directive : require
#include "patterns.glsl"
#include "halton.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform Probe {
    uint kind;           // 0 PCF disc, 1 Crytek ball, 2 thesis AO pattern, 3 eq 8 steps,
                         // 4 radical inverses (bases 2, 3, 5), 5 Halton hemisphere + step
    uint count;          // taps per pattern (kind 2: directions; kind 3: steps)
    uint first_pattern;
    uint patterns;
    float near_px;       // kind 3: eq 8's near and far [px]
    float far_px;
} probe;

layout(set = 0, binding = 0, std430) buffer Offsets {
    vec4 offsets[];
};

void main() {
    uint taps = probe.kind == 2u || probe.kind >= 4u ? 1u : probe.count;
    uint x = gl_GlobalInvocationID.x;
    if (x >= taps * probe.patterns) return;
    uint tap = x % taps;
    uint pattern = probe.first_pattern + x / taps;
    uint y = gl_GlobalInvocationID.y;
    ivec2 pixel = ivec2(y, 3u * y);
    vec4 o = vec4(0.0);
    if (probe.kind == 0u) o.xy = pcf_disc_offset(tap, probe.count, pattern, pixel);
    else if (probe.kind == 1u) o.xyz = crytek_offset(tap, probe.count, pattern);
    else if (probe.kind == 2u) o.xy = ao_thesis_pattern(pattern, probe.count);
    else if (probe.kind == 3u) o.x = ao_step_px(tap, probe.count, probe.near_px, probe.far_px);
    else if (probe.kind == 4u)
        o.xyz = vec3(radical_inverse(pattern, 2u), radical_inverse(pattern, 3u), radical_inverse(pattern, 5u));
    else {
        // Row y: a normal turned about two axes, and the Cranley-Patterson shift of pixel
        // (y, 3 y), as the estimators use it.
        float a = 0.7 * float(y);
        vec3 n = normalize(vec3(sin(a) * cos(2.3 * a), cos(a), sin(a) * sin(2.3 * a)));
        vec2 shift = halton_pixel_shift(pixel);
        o.xyz = halton_hemisphere(halton_point(pattern, shift), n);
        o.w = halton_step(pattern, fract(shift.x + shift.y));
    }
    offsets[y * taps * probe.patterns + x] = o;
}
