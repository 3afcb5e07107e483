#version 460
// 5x5 Gaussian blur (binomial 1 4 6 4 1 weights) of the AO: the thesis's no-reuse baseline
// (Table 4.1, "blur: 5x5 Gaussian"). Background taps are left out and the weights renormalised.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D ao_in;
layout(set = 1, binding = 2, rgba16f) uniform writeonly image2D ao_out;

const float W[5] = float[5](1.0, 4.0, 6.0, 4.0, 1.0);

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (outside_frame(q)) continue;
            if (texelFetch(g_position, q, 0).w == 0.0) continue;
            float w = W[i + 2] * W[j + 2];
            sum += w * texelFetch(ao_in, q, 0);
            weight += w;
        }
    }
    vec4 ao = weight > 0.0 ? sum / weight : texelFetch(ao_in, pixel, 0);
    imageStore(ao_out, pixel, ao);
}
