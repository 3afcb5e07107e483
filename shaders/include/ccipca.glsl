// CCIPCA on the GPU (Weng et al. 2003 as Chen, Lei & Chang 2012 use it; the CPU model with
// the equations is src/reference/ccipca.rs). Every pass works on 16x16 pixel groups and sees
// the same buffers: the k bases (v_i unnormalized, rgb per pixel, basis-major; basis 0's a
// holds the pixel's sample count n_p, so that the warp carries it), each pixel's residual u
// (rgb, and n_p again in a), the per-group partial sums and the image-wide sums. build.rs
// generates the Rust struct `CcipcaPush` from the push block.
#ifndef CCIPCA_GLSL
#define CCIPCA_GLSL

#include "frame.glsl"

layout(push_constant) uniform Ccipca {
    uint basis;     // the basis this dispatch works on (sums: the basis whose sums are finished)
    uint bases;     // k
    uint groups;    // 16x16 groups covering the image (partial sums per basis)
    uint max_age;   // a pixel's sample count stops at this
    uint restart;   // 1: every pixel starts over (bases zero, no samples)
    float amnesic;  // Weng's l: a pixel's step is (1 + l) / (n + l)
    uint frames;    // frames since the bases restarted (capped at max_age): n of uniform weighting
    uint per_pixel_bases; // the first this many bases step by the pixel's own count (per-pixel weighting)
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
// Per group, SUM_VEC4S vec4 of partial sums (pixel_sums, or the orthogonalization's).
layout(set = 1, binding = 8, std430) buffer Partials { vec4 partials[]; };
#endif
#ifdef CCIPCA_TOTALS
// Per basis, the image-wide sums of the same SUM_VEC4S vec4.
layout(set = 1, binding = 9, std430) buffer Totals { vec4 totals[]; };
#endif
#ifdef CCIPCA_BASES_PREV
// Last frame's bases, which the warp reads.
layout(set = 1, binding = 11, std430) readonly buffer BasesPrev { vec4 bases_prev[]; };
#endif

const uint GROUP_THREADS = 256u;
// Sums stored per group and per basis: eight for an update (pixel_sums), up to 14 for the
// orthogonalization of basis j (its dot products with the j before it and their squared
// lengths).
const uint SUM_VEC4S = 4u;

uint pixel_index(ivec2 p) {
    return uint(p.y) * frame.size.x + uint(p.x);
}

uint basis_index(uint i, uint pixel) {
    return i * frame.size.x * frame.size.y + pixel;
}

// The step of basis `i` at a pixel that has seen `n` samples: from n under per-pixel
// weighting, from the frames since the restart otherwise.
float ccipca_step(float n, uint i) {
    float age = i < ccipca.per_pixel_bases ? n : float(ccipca.frames);
    return (1.0 + ccipca.amnesic) / (max(age, 1.0) + ccipca.amnesic);
}

// The eight sums one basis update needs, for residual u, basis v and step a at one pixel
// (w = 1 - a). With s = (u.v) / |v| the new basis is v' = w v + a s u per pixel, so u.v' and
// |v'|^2 follow from these without a second pass over the image:
//   (u.v, |v|^2, w u.v, a |u|^2) and (w^2 |v|^2, w a u.v, a^2 |u|^2, |u|^2).
void pixel_sums(vec3 u, vec3 v, float a, out vec4 s[4]) {
    float uv = dot(u, v), vv = dot(v, v), uu = dot(u, u), w = 1.0 - a;
    s[0] = vec4(uv, vv, w * uv, a * uu);
    s[1] = vec4(w * w * vv, w * a * uv, a * a * uu, uu);
    s[2] = vec4(0.0);
    s[3] = vec4(0.0);
}

shared vec4 group_sums[SUM_VEC4S][GROUP_THREADS];

// Tree sum of the group's pixel sums; the first invocation gets the total. Every invocation
// of the group must call it (it has barriers).
void group_sum(inout vec4 s[SUM_VEC4S]) {
    uint t = gl_LocalInvocationIndex;
    for (uint m = 0u; m < SUM_VEC4S; ++m) group_sums[m][t] = s[m];
    barrier();
    for (uint stride = GROUP_THREADS / 2u; stride > 0u; stride >>= 1u) {
        if (t < stride) {
            for (uint m = 0u; m < SUM_VEC4S; ++m) group_sums[m][t] += group_sums[m][t + stride];
        }
        barrier();
    }
    for (uint m = 0u; m < SUM_VEC4S; ++m) s[m] = group_sums[m][0];
}

#ifdef CCIPCA_PARTIALS
// Write this group's partial sums for the next sums dispatch to finish.
void store_partials(vec4 s[SUM_VEC4S]) {
    group_sum(s);
    if (gl_LocalInvocationIndex == 0u) {
        uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        for (uint m = 0u; m < SUM_VEC4S; ++m) partials[SUM_VEC4S * g + m] = s[m];
    }
}
#endif

#ifdef CCIPCA_BASES
// Orthogonalization sums for basis j at pixel p (j >= 1): v_j . v_i for i < j in floats
// 0..6, |v_i|^2 in floats 7..13.
void ortho_sums(uint j, uint p, out vec4 s[SUM_VEC4S]) {
    float f[16];
    for (uint m = 0u; m < 16u; ++m) f[m] = 0.0;
    vec3 vj = bases[basis_index(j, p)].rgb;
    for (uint i = 0u; i < j; ++i) {
        vec3 vi = bases[basis_index(i, p)].rgb;
        f[i] = dot(vj, vi);
        f[7u + i] = dot(vi, vi);
    }
    for (uint m = 0u; m < SUM_VEC4S; ++m) s[m] = vec4(f[4u * m], f[4u * m + 1u], f[4u * m + 2u], f[4u * m + 3u]);
}
#endif

#endif // CCIPCA_GLSL
