#version 460
// SSAO with temporal reuse: dispatched indirectly over the 8x8 blocks the reprojection pass
// listed; evaluates one rotated pattern per pixel that is new or accumulating and merges it
// with eqs 4-5 (or EMA / mean); pixels of the refresh tile are recomputed from scratch with
// every pattern up to the rotation limit. Converged pixels are left alone.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D random_vectors;
layout(set = 1, binding = 3, r32ui) uniform readonly uimage2D state_in;
layout(set = 1, binding = 4, rgba16f) uniform image2D ao_cur;

#include "ao.glsl"

shared uint block_computed;

void main() {
    if (gl_LocalInvocationIndex == 0u) block_computed = 0u;
    barrier();
    uint packed = counters.blocks[gl_WorkGroupID.x];
    ivec2 pixel = ivec2(packed & 0xffffu, packed >> 16) * 8 + ivec2(gl_LocalInvocationID.xy);
    if (all(lessThan(uvec2(pixel), frame.size.xy))) {
        uint state = imageLoad(state_in, pixel).r;
        if (state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH) {
            vec4 position = texelFetch(g_position, pixel, 0);
            vec3 n = texelFetch(g_normal, pixel, 0).xyz;
            vec2 history = imageLoad(ao_cur, pixel).rg;
            vec2 result;
            uint limit = frame.temporal.w;
            if (state == STATE_REFRESH) {
                float occlusion = ao_estimate(pixel, position.xyz, n, 0.0, limit);
                result = vec2(1.0 - occlusion, float(limit));
            } else {
                // Each pixel walks through patterns 0, 1, ... in the order it accumulates them.
                float count = history.y;
                float fresh = 1.0 - ao_estimate(pixel, position.xyz, n, count, 1u);
                result = vec2(accumulate(history.x, fresh, count), count + 1.0);
            }
            imageStore(ao_cur, pixel, vec4(clamp(result.x, 0.0, 1.0), result.y, 0.0, 0.0));
            atomicAdd(block_computed, 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && block_computed > 0u)
        atomicAdd(counters.ssao_computed_pixels, block_computed);
}
