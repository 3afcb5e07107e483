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

// Fresh estimate for a pixel (rgb) and the mean squared luminance of its patterns (a): in the
// refresh tile the mean of every pattern up to the rotation limit (a recompute from scratch,
// the estimator accumulation converges to), else this frame's pattern.
vec4 fresh_gather(vec3 p, vec3 n, bool refresh, ivec2 seed_pixel) {
    uint first = refresh ? 0u : effect.pattern;
    uint patterns = refresh ? frame.rotation_limit : 1u;
    vec3 sum = vec3(0.0);
    float sum2 = 0.0;
    for (uint j = 0u; j < patterns; ++j) {
        vec3 x = rsm_gather(p, n, float(first + j), 1u, seed_pixel);
        float l = dot(x, LUMA);
        sum += x;
        sum2 += l * l;
    }
    return vec4(sum, sum2) / float(patterns);
}

// The value a pass computes for a pixel at p (rgb, a = mean squared luminance of its
// patterns): the gather, or with the test input (IndirectInput::Ramp) p itself, a linear
// function with a known value at every pixel.
vec4 indirect_value(vec3 p, vec3 n, bool refresh, ivec2 seed_pixel) {
    if (frame.indirect_ramp != 0u) return vec4(p, dot(p, LUMA) * dot(p, LUMA));
    return fresh_gather(p, n, refresh, seed_pixel);
}

#endif // INDIRECT_COMMON_GLSL
