#version 460
// 16x supersampling's resolve: each output pixel is the box filter of the 4x4 rendered pixels
// it covers, in display-linear colour (the composite's tonemapped image), then sRGB-encoded.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "srgb.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D shaded;
layout(set = 1, binding = 1, rgba8) uniform writeonly image2D out_color;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(out_color)))) return;
    vec3 sum = vec3(0.0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) sum += texelFetch(shaded, pixel * 4 + ivec2(x, y), 0).rgb;
    vec3 color = sum / 16.0;
    imageStore(out_color, pixel, vec4(srgb_encode(clamp(color, 0.0, 1.0)), 1.0));
}
