// Shared by the indirect-light passes: the RSM inputs and the pattern choice.
#ifndef INDIRECT_COMMON_GLSL
#define INDIRECT_COMMON_GLSL

#include "frame.glsl"
#include "effect.glsl"

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D rsm_position;
layout(set = 1, binding = 3) uniform texture2D rsm_normal;
layout(set = 1, binding = 4) uniform texture2D rsm_flux;

// After the bindings it reads.
#include "rsm_gather.glsl"

// Fresh estimate for a pixel: every pattern up to the rotation limit in the refresh tile (a
// recompute from scratch), else this frame's pattern.
vec3 fresh_gather(vec3 p, vec3 n, bool refresh, ivec2 seed_pixel) {
    return refresh ? rsm_gather(p, n, 0.0, frame.rotation_limit, seed_pixel)
                   : rsm_gather(p, n, float(effect.pattern), 1u, seed_pixel);
}

// The value a pass computes for a pixel at p: the gather, or with the test input
// (IndirectInput::Ramp) p itself, a linear function with a known value at every pixel.
vec3 indirect_value(vec3 p, vec3 n, bool refresh, ivec2 seed_pixel) {
    return frame.indirect_ramp != 0u ? p : fresh_gather(p, n, refresh, seed_pixel);
}

#endif // INDIRECT_COMMON_GLSL
