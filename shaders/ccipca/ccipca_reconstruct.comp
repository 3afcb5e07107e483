#version 460
// CCIPCA's output: the noisy image projected on the updated bases, x - u_{k+1}. Light is not
// negative; a projection can be where the bases have not yet learned a region, so it is
// clamped at zero. The clamp raises the mean where a projection overshoots below zero, and
// lowers the error more than that bias costs; under the defaults nothing is negative, so it
// changes nothing there (figures: docs/results/DECISIONS.md, "CCIPCA's clamp at zero").
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#define CCIPCA_RESIDUAL
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 5) uniform texture2D noisy;
layout(set = 1, binding = 10, rgba32f) uniform writeonly image2D filtered;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 x = texelFetch(noisy, pixel, 0).rgb;
    vec3 u = residual[pixel_index(pixel)].rgb;
    imageStore(filtered, pixel, vec4(max(x - u, vec3(0.0)), 1.0));
}
