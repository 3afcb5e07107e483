#version 460
// CCIPCA: one group adds the partial sums of every 16x16 group into basis `basis`'s
// image-wide sums (the GPU reduction that keeps the updates and the orthogonalization free of
// CPU round trips). `gram`: the sums are the warped bases' Gram matrix, from which the first
// invocation derives the orthogonalization's transform (Chen et al.'s Algorithm 2, in the
// space of the k bases): each basis loses its projections on the bases before it
// (Gram-Schmidt without normalization, so the lengths that estimate the eigenvalues stay).
// The transform is found on the unit bases (the Gram matrix scaled to correlations: diagonal
// 1, cosines elsewhere), so that bases whose lengths differ by orders of magnitude lose no
// precision; Gram-Schmidt commutes with scaling, so T_jm = T'_jm |v_j| / |v_m|. A basis of
// length zero (not started, or seen by no kept pixel) stays zero and takes nothing out.
// @permutation : BASIS_SUMS
// @permutation gram: GRAM
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 256) in;

#ifdef GRAM
// T from the Gram matrix `g` (packed upper triangle), into totals at TRANSFORM_OFFSET.
void store_transform(vec4 sums[SUM_VEC4S]) {
    float g[4u * SUM_VEC4S];
    for (uint m = 0u; m < SUM_VEC4S; ++m) {
        g[4u * m] = sums[m].x;
        g[4u * m + 1u] = sums[m].y;
        g[4u * m + 2u] = sums[m].z;
        g[4u * m + 3u] = sums[m].w;
    }
    float len[MAX_BASES];
    for (uint i = 0u; i < BASES; ++i) len[i] = sqrt(max(g[gram_index(i, i)], 0.0));
    #define CORR(i, j) (len[i] > 0.0 && len[j] > 0.0 ? g[gram_index(min(i, j), max(i, j))] / (len[i] * len[j]) : 0.0)
    // Row by row: u'_j = u_j - sum_{i<j} (u_j . u'_i) / |u'_i|^2 u'_i, with
    // u_j . u'_i = sum_m T'_im c_jm and |u'_i|^2 = u'_i . u_i.
    float t[MAX_BASES][MAX_BASES];
    float norm2[MAX_BASES];
    for (uint j = 0u; j < BASES; ++j) {
        for (uint m = 0u; m < BASES; ++m) t[j][m] = m == j ? 1.0 : 0.0;
        for (uint i = 0u; i < j; ++i) {
            float d = 0.0;
            for (uint m = 0u; m <= i; ++m) d += t[i][m] * CORR(j, m);
            float coeff = norm2[i] > 0.0 ? d / norm2[i] : 0.0;
            for (uint m = 0u; m <= i; ++m) t[j][m] -= coeff * t[i][m];
        }
        float n2 = 0.0;
        for (uint m = 0u; m <= j; ++m) n2 += t[j][m] * CORR(j, m);
        norm2[j] = len[j] > 0.0 ? max(n2, 0.0) : 0.0;
    }
    #undef CORR
    for (uint j = 0u; j < BASES; ++j) {
        float row[MAX_BASES];
        for (uint m = 0u; m < MAX_BASES; ++m) {
            row[m] = m < BASES && m <= j && len[m] > 0.0 ? t[j][m] * len[j] / len[m] : 0.0;
        }
        totals[TRANSFORM_OFFSET + 2u * j] = vec4(row[0], row[1], row[2], row[3]);
        totals[TRANSFORM_OFFSET + 2u * j + 1u] = vec4(row[4], row[5], row[6], row[7]);
    }
}
#endif

void main() {
    vec4 s[SUM_VEC4S] = NO_SUMS;
    uint count = min(ccipca.sum_vec4s, SUM_VEC4S);
    for (uint g = gl_LocalInvocationIndex; g < ccipca.groups; g += GROUP_THREADS) {
        for (uint m = 0u; m < count; ++m) s[m] += partials[SUM_VEC4S * g + m];
    }
    group_sum(s, count);
    if (gl_LocalInvocationIndex == 0u) {
        for (uint m = 0u; m < count; ++m) totals[SUM_VEC4S * ccipca.basis + m] = s[m];
#ifdef GRAM
        store_transform(s);
#endif
    }
}
