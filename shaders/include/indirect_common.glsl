// Shared by the indirect-light passes: the RSM inputs and the pattern choice.
#ifndef INDIRECT_COMMON_GLSL
#define INDIRECT_COMMON_GLSL

#include "frame.glsl"
#include "effect.glsl"
#include "temporal.glsl"

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D rsm_position;
layout(set = 1, binding = 3) uniform texture2D rsm_normal;
layout(set = 1, binding = 4) uniform texture2D rsm_flux;

// After the bindings it reads.
#include "rsm_gather.glsl"

// One pattern's estimate for a pixel at p (rgb) and its squared luminance (a): the gather, or
// with the test input (IndirectInput::Ramp) p itself, a linear function with a known value at
// every pixel.
vec4 indirect_pattern(vec3 p, vec3 n, uint pattern, ivec2 seed_pixel) {
    vec3 x = frame.indirect_ramp != 0u ? p : rsm_gather(p, n, float(pattern), 1u, seed_pixel);
    float l = dot(x, LUMA);
    return vec4(x, l * l);
}

// This frame's estimate (its pattern) for a pixel at p.
vec4 indirect_value(vec3 p, vec3 n, ivec2 seed_pixel) {
    return indirect_pattern(p, n, effect.pattern, seed_pixel);
}

#endif // INDIRECT_COMMON_GLSL
