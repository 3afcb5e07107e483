#version 460
// CCIPCA: one group adds the partial sums of every 16x16 group into basis `basis`'s
// image-wide sums (the GPU reduction that keeps the updates and the orthogonalization free of
// CPU round trips).
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 256) in;

void main() {
    vec4 s[SUM_VEC4S] = vec4[](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    for (uint g = gl_LocalInvocationIndex; g < ccipca.groups; g += GROUP_THREADS) {
        for (uint m = 0u; m < SUM_VEC4S; ++m) s[m] += partials[SUM_VEC4S * g + m];
    }
    group_sum(s);
    if (gl_LocalInvocationIndex == 0u) {
        for (uint m = 0u; m < SUM_VEC4S; ++m) totals[SUM_VEC4S * ccipca.basis + m] = s[m];
    }
}
