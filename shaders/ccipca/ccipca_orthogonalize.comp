#version 460
// Chen et al.'s Algorithm 2 after the warp, in one pass: every basis becomes its row of the
// transform the sums pass derived from the warped bases' Gram matrix (shaders/ccipca/ccipca_sums.comp,
// `gram`), v'_j = sum over m <= j of T_jm v_m, so the bases are read and written once. A warp
// adds and removes dimensions, which breaks the orthogonality CCIPCA's updates assume.
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_BASES
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    uint p = pixel_index(pixel);
    vec3 v[MAX_BASES];
    for (uint m = 0u; m < BASES; ++m) v[m] = bases[basis_index(m, p)].rgb;
    for (uint j = 1u; j < BASES; ++j) {
        vec4 lo = totals[TRANSFORM_OFFSET + 2u * j], hi = totals[TRANSFORM_OFFSET + 2u * j + 1u];
        float row[MAX_BASES] = float[](lo.x, lo.y, lo.z, lo.w, hi.x, hi.y, hi.z, hi.w);
        vec3 out_j = vec3(0.0);
        for (uint m = 0u; m <= j; ++m) out_j += row[m] * v[m];
        bases[basis_index(j, p)] = vec4(out_j, 0.0);
    }
}
