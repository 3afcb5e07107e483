#version 460
// Chen et al.'s Algorithm 2 after the warp: basis `basis` (j >= 1) loses its projections on
// the bases before it, already orthogonal, from the image-wide sums (ortho_sums); stores the
// sums for basis j + 1. A warp adds and removes dimensions, which breaks the bases'
// orthogonality that CCIPCA's updates assume.
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_BASES
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint j = ccipca.basis;
    vec4 s[SUM_VEC4S] = vec4[](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    if (!outside_frame(pixel)) {
        uint p = pixel_index(pixel);
        float f[16];
        for (uint m = 0u; m < SUM_VEC4S; ++m) {
            vec4 t = totals[SUM_VEC4S * j + m];
            f[4u * m] = t.x;
            f[4u * m + 1u] = t.y;
            f[4u * m + 2u] = t.z;
            f[4u * m + 3u] = t.w;
        }
        vec3 v = bases[basis_index(j, p)].rgb;
        for (uint i = 0u; i < j; ++i) {
            // A zero basis (not started) takes nothing out.
            float coeff = f[7u + i] > 0.0 ? f[i] / f[7u + i] : 0.0;
            v -= coeff * bases[basis_index(i, p)].rgb;
        }
        bases[basis_index(j, p)] = vec4(v, 0.0);
        if (j + 1u < ccipca.bases) ortho_sums(j + 1u, p, s);
    }
    if (j + 1u < ccipca.bases) store_partials(s);
}
