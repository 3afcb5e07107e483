#version 460
// SSAO without reuse: every pixel, every frame, `patterns` patterns starting at the pattern
// base (the fixed pattern 0 for the thesis's no-reuse baseline; many from an index range no
// accumulation reaches for references).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#define COUNTERS_BINDING 4
#include "counters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D random_vectors;
// ao_position_chain.comp's point-sampled levels 1-3 of g_position (far taps).
layout(set = 1, binding = 7) uniform texture2D g_position_1;
layout(set = 1, binding = 8) uniform texture2D g_position_2;
layout(set = 1, binding = 9) uniform texture2D g_position_3;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D ao_out;

#include "ao.glsl"

shared uint block_computed;

void main() {
    if (gl_LocalInvocationIndex == 0u) block_computed = 0u;
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!outside_frame(pixel)) {
        vec4 position = texelFetch(g_position, pixel, 0);
        float visibility = 1.0;
        if (position.w != 0.0) {
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            visibility = 1.0 - ao_estimate(g_position, g_position_1, g_position_2, g_position_3, g_normal, random_vectors, pixel, position.xyz, n,
                                           float(ao.pattern_base), ao.patterns);
            atomicAdd(block_computed, 1u);
        }
        imageStore(ao_out, pixel, vec4(visibility, 0.0, 0.0, float(ao.patterns)));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && block_computed > 0u)
        atomicAdd(counters.computed_pixels, block_computed);
}
