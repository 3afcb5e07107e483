#version 460
// CCIPCA, one basis at a time from its image-wide sums (ccipca.glsl).
// `update`: update basis `basis` at every pixel, take its projection out of the residual,
// and store the group's sums for the next basis.
// `project` (--ccipca-project before): take the projection of the residual on last frame's
// basis `basis` out of it, leaving the basis as it is; after the last basis write the
// reconstruction x - u_{k+1}, restart the residual at x and store the sums with which the
// updates begin.
// @permutation update: UPDATE
// @permutation project: PROJECT
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#define CCIPCA_BASES
#define CCIPCA_RESIDUAL
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

#ifdef PROJECT
layout(set = 1, binding = 5) uniform texture2D noisy;
layout(set = 1, binding = 10, rgba32f) uniform writeonly image2D filtered;
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = !outside_frame(pixel);
    uint i = ccipca.basis;
    vec4 s[SUM_VEC4S] = NO_SUMS;
    if (inside) {
        uint p = pixel_index(pixel);
        vec4 t0 = totals[SUM_VEC4S * i], t1 = totals[SUM_VEC4S * i + 1u];
        vec4 r = residual[p];
        vec3 u = r.rgb;
        uint b = basis_index(i, p);
        vec4 stored = bases[b];
        vec3 v = stored.rgb;
#ifdef PROJECT
        // u . v / |v|^2 from the first two sums; a basis not yet started takes nothing out.
        u -= (t0.y > 0.0 ? t0.x / t0.y : 0.0) * v;
        if (i + 1u < BASES) {
            residual[p] = vec4(u, r.a);
            pixel_sums(u, bases[basis_index(i + 1u, p)].rgb, ccipca_step(r.a, i + 1u), s);
        } else {
            vec3 x = texelFetch(noisy, pixel, 0).rgb;
            // Clamped as in ccipca_reconstruct.comp (which measures what the clamp costs).
            imageStore(filtered, pixel, vec4(max(x - u, vec3(0.0)), 1.0));
            residual[p] = vec4(x, r.a);
            pixel_sums(x, bases[p].rgb, ccipca_step(r.a, 0u), s);
        }
#else
        float a = ccipca_step(r.a, i);
        // |v|^2 = 0: a basis not yet started takes the residual (Weng's case i = n).
        float uv_new = t1.w, vv_new = t1.w;
        if (t0.y > 0.0) {
            float s = t0.x * inversesqrt(t0.y);
            v = (1.0 - a) * v + (a * s) * u;
            uv_new = t0.z + s * t0.w;
            vv_new = t1.x + 2.0 * s * t1.y + s * s * t1.z;
        } else {
            v = u;
        }
        // u . v' / |v'|^2; a basis that is still zero takes nothing out.
        float coeff = vv_new > 0.0 ? uv_new / vv_new : 0.0;
        u -= coeff * v;
        // Basis 0's a: the pixel's sample count, kept.
        bases[b] = vec4(v, stored.a);
        residual[p] = vec4(u, r.a);
        if (i + 1u < BASES) pixel_sums(u, bases[basis_index(i + 1u, p)].rgb, ccipca_step(r.a, i + 1u), s);
#endif
    }
#ifdef PROJECT
    store_partials(s, UPDATE_SUM_VEC4S);
#else
    if (i + 1u < BASES) store_partials(s, UPDATE_SUM_VEC4S);
#endif
}
