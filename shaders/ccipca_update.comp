#version 460
// CCIPCA: update basis `basis` at every pixel from its image-wide sums (ccipca.glsl), take
// its projection out of the residual, and store the group's sums for the next basis.
#extension GL_GOOGLE_include_directive : require
#define CCIPCA_BASES
#define CCIPCA_RESIDUAL
#define CCIPCA_PARTIALS
#define CCIPCA_TOTALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = !outside_frame(pixel);
    vec4 s[SUM_VEC4S] = NO_SUMS;
    if (inside) {
        uint i = ccipca.basis;
        uint p = pixel_index(pixel);
        vec4 t0 = totals[SUM_VEC4S * i], t1 = totals[SUM_VEC4S * i + 1u];
        vec4 r = residual[p];
        vec3 u = r.rgb;
        float a = ccipca_step(r.a, i);
        uint b = basis_index(i, p);
        vec3 v = bases[b].rgb;
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
        bases[b] = vec4(v, i == 0u ? r.a : 0.0);
        residual[p] = vec4(u, r.a);
        if (i + 1u < BASES) pixel_sums(u, bases[basis_index(i + 1u, p)].rgb, ccipca_step(r.a, i + 1u), s);
    }
    if (ccipca.basis + 1u < BASES) store_partials(s, UPDATE_SUM_VEC4S);
}
