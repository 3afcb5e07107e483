#version 460
// CCIPCA's warp (Chen et al. section 3.4): every basis and each pixel's sample count follow the
// pixel's surface from last frame's screen to this one's (previous_texel.glsl: eq 1, the
// nearest texel, kept where eq 3's test holds and it faces the same way). A pixel new to the
// view is a new dimension: zero in every basis, no samples, so per-pixel weighting lets it take
// full steps. Stores the group's part of the warped bases' Gram matrix, which the
// orthogonalization works from.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define CCIPCA_BASES
#define CCIPCA_BASES_PREV
#define CCIPCA_PARTIALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D prev_position;
layout(set = 1, binding = 3) uniform texture2D prev_normal;
layout(set = 1, binding = 4) uniform texture2D g_motion; // world-space motion since last frame
#include "previous_texel.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    float gram[4u * SUM_VEC4S];
    for (uint m = 0u; m < 4u * SUM_VEC4S; ++m) gram[m] = 0.0;
    if (!outside_frame(pixel)) {
        uint p = pixel_index(pixel);
        ivec2 t = previous_texel(pixel);
        bool kept = t.x >= 0;
        uint q = kept ? pixel_index(t) : 0u;
        vec3 v[MAX_BASES];
        for (uint j = 0u; j < BASES; ++j) {
            vec4 b = kept ? bases_prev[basis_index(j, q)] : vec4(0.0);
            bases[basis_index(j, p)] = b;
            v[j] = b.rgb;
            for (uint i = 0u; i <= j; ++i) gram[gram_index(i, j)] = dot(v[i], v[j]);
        }
    }
    vec4 s[SUM_VEC4S];
    for (uint m = 0u; m < SUM_VEC4S; ++m) s[m] = vec4(gram[4u * m], gram[4u * m + 1u], gram[4u * m + 2u], gram[4u * m + 3u]);
    store_partials(s, gram_vec4s(BASES));
}
