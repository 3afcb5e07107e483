// CCIPCA on the GPU (Weng et al. 2003 as Chen, Lei & Chang 2012 use it; the CPU model with
// the equations is src/reference/ccipca.rs). Every pass works on 16x16 pixel groups and sees
// the same buffers: the k bases (v_i unnormalized, rgb per pixel, basis-major; basis 0's a
// holds the pixel's sample count n_p, so that the warp carries it), each pixel's residual u
// (rgb, and in a the count this frame's steps are taken from: n_p, or less for a sample
// worth more than one, see indirect_noisy.comp), the per-group partial sums and the
// image-wide sums. build.rs generates the Rust struct `CcipcaPush` from the push block.
#ifndef CCIPCA_GLSL
#define CCIPCA_GLSL

#include "frame.glsl"

// k, fixed when the pipelines are made: the loops over bases unroll and the per-pixel arrays
// stay in registers.
layout(constant_id = 0) const uint BASES = 3u;

layout(push_constant) uniform Ccipca {
    uint basis;     // the basis this dispatch works on (sums: the basis whose sums are finished)
    uint groups;    // 16x16 groups covering the image (partial sums per basis)
    uint max_age;   // a pixel's sample count stops at this
    uint restart;   // 1: every pixel starts over (bases zero, no samples)
    float amnesic;  // Weng's l: a pixel's step is (1 + l) / (n + l)
    uint frames;    // frames since the bases restarted (capped at max_age): n of uniform weighting
    uint per_pixel_bases; // the first this many bases step by the pixel's own count (per-pixel weighting)
    uint sum_vec4s; // vec4 of sums this dispatch stores or adds up (at most SUM_VEC4S)
    uint filter_radius; // basis filtering: the joint bilateral filter's radius [px]
    uint new_pixel_vpls; // adaptive sampling: VPLs of a pixel new to the view (0 = as any other)
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
// IndirectConfig::MAX_BASES.
const uint MAX_BASES = 8u;
// Room for sums per group and per basis: eight for an update (pixel_sums, 2 vec4), or the
// Gram matrix of the warped bases (k (k + 1) / 2 <= 36 dot products, 9 vec4).
const uint SUM_VEC4S = 9u;
// Where in `totals` the sums pass's `gram` permutation leaves the orthogonalization's
// transform (MAX_BASES x MAX_BASES floats, row j: v'_j's weights on the warped v_m).
const uint TRANSFORM_OFFSET = SUM_VEC4S;

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
const uint UPDATE_SUM_VEC4S = 2u;
void pixel_sums(vec3 u, vec3 v, float a, inout vec4 s[SUM_VEC4S]) {
    float uv = dot(u, v), vv = dot(v, v), uu = dot(u, u), w = 1.0 - a;
    s[0] = vec4(uv, vv, w * uv, a * uu);
    s[1] = vec4(w * w * vv, w * a * uv, a * a * uu, uu);
}

// A zeroed set of sums.
#define NO_SUMS vec4[SUM_VEC4S](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0))

shared vec4 group_sums[GROUP_THREADS];

// Tree sum over the group of each of the first `count` vec4, one after another (so that the
// shared memory stays at 4 KB); the first invocation gets the totals. Every invocation of the
// group must call it (it has barriers).
void group_sum(inout vec4 s[SUM_VEC4S], uint count) {
    uint t = gl_LocalInvocationIndex;
    for (uint m = 0u; m < count; ++m) {
        group_sums[t] = s[m];
        barrier();
        for (uint stride = GROUP_THREADS / 2u; stride > 0u; stride >>= 1u) {
            if (t < stride) group_sums[t] += group_sums[t + stride];
            barrier();
        }
        s[m] = group_sums[0];
        barrier();
    }
}

#ifdef CCIPCA_PARTIALS
// Write this group's partial sums (the first `count` vec4) for the next sums dispatch.
void store_partials(vec4 s[SUM_VEC4S], uint count) {
    group_sum(s, count);
    if (gl_LocalInvocationIndex == 0u) {
        uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        for (uint m = 0u; m < count; ++m) partials[SUM_VEC4S * g + m] = s[m];
    }
}
#endif

// Index of v_i . v_j (i <= j) in the packed upper triangle of the Gram matrix.
uint gram_index(uint i, uint j) {
    return j * (j + 1u) / 2u + i;
}

// vec4 holding the Gram matrix of `k` bases.
uint gram_vec4s(uint k) {
    return (k * (k + 1u) / 2u + 3u) / 4u;
}

#endif // CCIPCA_GLSL
