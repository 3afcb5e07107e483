#version 460
// CCIPCA: one group adds the partial sums of every 16x16 group into basis `basis`'s
// image-wide sums (the GPU reduction that keeps the update free of CPU round trips).
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 256) in;

void main() {
    vec4 s0 = vec4(0.0), s1 = vec4(0.0);
    for (uint g = gl_LocalInvocationIndex; g < ccipca.groups; g += GROUP_THREADS) {
        s0 += partials[2u * g];
        s1 += partials[2u * g + 1u];
    }
    group_sum(s0, s1);
    if (gl_LocalInvocationIndex == 0u) {
        totals[2u * ccipca.basis] = s0;
        totals[2u * ccipca.basis + 1u] = s1;
    }
}
