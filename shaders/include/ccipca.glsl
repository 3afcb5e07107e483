// CCIPCA on the GPU (Weng et al. 2003 as Chen, Lei & Chang 2012 use it; the CPU model with
// the equations is src/reference/ccipca.rs). Every pass works on 16x16 pixel groups and sees
// the same buffers: the k bases (v_i unnormalized, rgb per pixel, basis-major), each pixel's
// residual u (rgb) and sample count n_p (a), the per-group partial sums and the image-wide
// sums per basis. build.rs generates the Rust struct `CcipcaPush` from the push block.
#ifndef CCIPCA_GLSL
#define CCIPCA_GLSL

#include "frame.glsl"

layout(push_constant) uniform Ccipca {
    uint basis;     // the basis this dispatch works on (sums: the basis whose sums are finished)
    uint bases;     // k
    uint groups;    // 16x16 groups covering the image (partial sums per basis)
    uint max_age;   // a pixel's sample count stops at this
    uint restart;   // 1: every pixel starts over (bases zero, no samples)
    float amnesic;  // Weng's l: a pixel's step is (1 + l) / (n_p + l)
} ccipca;

// Each shader defines the buffers it uses before including this (glslang keeps unused ones,
// and the reflection check holds every pass to its declared bindings).
#ifdef CCIPCA_BASES
layout(set = 1, binding = 6, std430) buffer Bases { vec4 bases[]; };
#endif
#ifdef CCIPCA_RESIDUAL
// rgb: the residual u_i of the basis being updated; a: samples seen (n_p).
layout(set = 1, binding = 7, std430) buffer Residual { vec4 residual[]; };
#endif
#ifdef CCIPCA_PARTIALS
// Per group, two vec4 of partial sums (pixel_sums below).
layout(set = 1, binding = 8, std430) buffer Partials { vec4 partials[]; };
#endif
#ifdef CCIPCA_TOTALS
// Per basis, two vec4 of image-wide sums (the same eight as the partials).
layout(set = 1, binding = 9, std430) buffer Totals { vec4 totals[]; };
#endif

const uint GROUP_THREADS = 256u;

uint pixel_index(ivec2 p) {
    return uint(p.y) * frame.size.x + uint(p.x);
}

uint basis_index(uint i, uint pixel) {
    return i * frame.size.x * frame.size.y + pixel;
}

float ccipca_step(float n) {
    return (1.0 + ccipca.amnesic) / (max(n, 1.0) + ccipca.amnesic);
}

// The eight sums one basis update needs, for residual u, basis v and step a at one pixel
// (w = 1 - a). With s = (u.v) / |v| the new basis is v' = w v + a s u per pixel, so u.v' and
// |v'|^2 follow from these without a second pass over the image:
//   (u.v, |v|^2, w u.v, a |u|^2) and (w^2 |v|^2, w a u.v, a^2 |u|^2, |u|^2).
void pixel_sums(vec3 u, vec3 v, float a, out vec4 s0, out vec4 s1) {
    float uv = dot(u, v), vv = dot(v, v), uu = dot(u, u), w = 1.0 - a;
    s0 = vec4(uv, vv, w * uv, a * uu);
    s1 = vec4(w * w * vv, w * a * uv, a * a * uu, uu);
}

shared vec4 sum_lo[GROUP_THREADS];
shared vec4 sum_hi[GROUP_THREADS];

// Tree sum of the group's pixel sums; the first invocation gets the total. Every invocation
// of the group must call it (it has barriers).
void group_sum(inout vec4 s0, inout vec4 s1) {
    uint t = gl_LocalInvocationIndex;
    sum_lo[t] = s0;
    sum_hi[t] = s1;
    barrier();
    for (uint stride = GROUP_THREADS / 2u; stride > 0u; stride >>= 1u) {
        if (t < stride) {
            sum_lo[t] += sum_lo[t + stride];
            sum_hi[t] += sum_hi[t + stride];
        }
        barrier();
    }
    s0 = sum_lo[0];
    s1 = sum_hi[0];
}

#ifdef CCIPCA_PARTIALS
// Write this group's partial sums for the basis the next sums dispatch finishes.
void store_partials(vec4 s0, vec4 s1) {
    group_sum(s0, s1);
    if (gl_LocalInvocationIndex == 0u) {
        uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        partials[2u * g] = s0;
        partials[2u * g + 1u] = s1;
    }
}
#endif

#endif // CCIPCA_GLSL
