#version 460
// Debug effect (`--effects normals`): each pixel's shading normal as radiance, n * 0.5 + 0.5,
// added by the composite like direct light: a look at the normals every other effect reads
// (two-sided flips, interpolation, the visibility buffer's rebuild). Background: nothing.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2, rgba32f) uniform writeonly image2D normals_out;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 radiance = vec3(0.0);
    if (texelFetch(g_position, pixel, 0).w != 0.0) {
        radiance = texelFetch(g_normal, pixel, 0).xyz * 0.5 + 0.5;
    }
    // A non-finite normal must not reach the composite (clamp would keep a NaN).
    if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
    imageStore(normals_out, pixel, vec4(radiance, 1.0));
}
