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

// One pattern's estimate for a pixel at p (rgb) and its squared luminance (a) from its share
// of the VPLs (rsm_gather; interleave 1: every VPL), or with the test input
// (IndirectInput::Ramp) p itself, a linear function with a known value at every pixel.
vec4 indirect_pattern(vec3 p, vec3 n, uint pattern, ivec2 pixel, uint interleave) {
    vec3 x = frame.indirect_input == 1u ? p : rsm_gather(p, n, pattern, pixel, interleave);
    float l = dot(x, LUMA);
    return vec4(x, l * l);
}

// This frame's estimate (its pattern) for a pixel at p with every VPL.
vec4 indirect_value(vec3 p, vec3 n, ivec2 pixel) {
    return indirect_pattern(p, n, effect.pattern, pixel, 1u);
}

// This frame's estimate for a pixel at p from its interleaved share of the VPLs
// (vpl_params.interleave).
vec4 indirect_share(vec3 p, vec3 n, ivec2 pixel) {
    return indirect_pattern(p, n, effect.pattern, pixel, vpl_params.interleave);
}

// One lane's part of pattern `pattern`'s every-VPL estimate (rgb only): the parts of lanes
// 0..lanes-1 sum to indirect_pattern(p, n, pattern, pixel, 1u).rgb.
vec3 indirect_part(vec3 p, vec3 n, uint pattern, ivec2 pixel, uint lane, uint lanes) {
    if (frame.indirect_input == 1u) return lane == 0u ? p : vec3(0.0);
    return rsm_gather_part(p, n, pattern, pixel, lane, lanes);
}

// World-space size of one pixel at p, at a sampling step of `step` full-resolution pixels.
float pixel_footprint(vec3 p, float step) {
    return 2.0 * distance(p, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y) * step;
}

// cos(25 degrees): neighbours on a surface turned further away belong to another surface.
const float NORMAL_ACCEPT = 0.9;
// Tangent-plane distance limit in pixel footprints: scale-free, as the footprint grows with
// the distance to the camera.
const float PLANE_ACCEPT = 2.0;

// Whether a sample at q (normal nq) lies on the surface of the pixel at p (normal n), whose
// footprint is `footprint`: used wherever one pixel's light stands in for another's.
bool same_surface(vec3 p, vec3 n, vec3 q, vec3 nq, float footprint) {
    return dot(nq, n) >= NORMAL_ACCEPT && abs(dot(n, q - p)) <= PLANE_ACCEPT * footprint;
}

#endif // INDIRECT_COMMON_GLSL
