#version 460
// Shadow visibility of every pixel, every frame: the grid PCF baseline (hard, 49 samples) or a
// disc kernel with the fixed pattern 0 (a Vogel spiral turned per pixel; references with many
// samples). r = visibility, a = samples.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D shadow_depth;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D visibility_out;

#include "shadow.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 position = texelFetch(g_position, pixel, 0);
    float v = 1.0;
    if (position.w != 0.0)
        v = shadow_visibility(position.xyz, texelFetch(g_normal, pixel, 0).xyz, 0.0, pixel);
    imageStore(visibility_out, pixel, vec4(v, 0.0, 0.0, 1.0));
}
