#version 460
// CCIPCA's basis filtering (Chen et al. Figure 6c): after the updates, every basis is smoothed
// by a joint bilateral filter of radius `filter_radius` into the other bases buffer, which the
// next frame works on. A basis is a learned image of the light and its variations, smooth
// wherever the light is; the noise of the samples it was updated from is not, and would reach
// every later projection. Weights as the joint bilateral baselines' (shaders/jbf/indirect_jbf.comp):
// Gaussian in screen distance (sigma = radius / 2), normal agreement ^16, tangent-plane
// distance in pixel footprints (sigma 2). Basis 0's sample counts are the pixel's own.
// Filtering each basis on its own tilts them towards each other (all lean to the smooth
// image); with --ccipca-orthogonalize always the pass also stores the filtered bases' Gram
// matrix partial sums, from which the orthogonalization (Algorithm 2, as after a warp) makes
// them orthogonal again.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#define CCIPCA_BASES
#define CCIPCA_BASES_PREV
#define CCIPCA_PARTIALS
#include "ccipca.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;

const float NORMAL_POWER = 16.0;
const float PLANE_SIGMA = 2.0; // pixel footprints

// The filtered bases of one pixel (background pixels keep theirs).
void filtered(ivec2 pixel, uint p, out vec4 v[MAX_BASES]) {
    for (uint i = 0u; i < BASES; ++i) v[i] = bases_prev[basis_index(i, p)];
    vec4 g = texelFetch(g_position, pixel, 0);
    if (g.w == 0.0) return;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float footprint = 2.0 * distance(g.xyz, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y);
    float inv_plane = 1.0 / max(PLANE_SIGMA * footprint, 1e-30);
    int r = int(ccipca.filter_radius);
    float sigma = 0.5 * float(max(r, 1));
    float inv_2s2 = 1.0 / (2.0 * sigma * sigma);
    vec3 sum[MAX_BASES];
    for (uint i = 0u; i < BASES; ++i) sum[i] = vec3(0.0);
    float weights = 0.0;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (outside_frame(q)) continue;
            vec4 gq = texelFetch(g_position, q, 0);
            if (gq.w == 0.0) continue;
            float plane = dot(n, gq.xyz - g.xyz) * inv_plane;
            float w = exp(-float(dx * dx + dy * dy) * inv_2s2 - plane * plane) *
                      pow(max(dot(n, texelFetch(g_normal, q, 0).xyz), 0.0), NORMAL_POWER);
            uint qi = pixel_index(q);
            for (uint i = 0u; i < BASES; ++i) sum[i] += w * bases_prev[basis_index(i, qi)].rgb;
            weights += w;
        }
    }
    // The centre weighs 1.
    float inv = 1.0 / max(weights, 1.0);
    for (uint i = 0u; i < BASES; ++i) v[i] = vec4(sum[i] * inv, i == 0u ? v[0].a : 0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    float gram[4u * SUM_VEC4S];
    for (uint m = 0u; m < 4u * SUM_VEC4S; ++m) gram[m] = 0.0;
    if (!outside_frame(pixel)) {
        uint p = pixel_index(pixel);
        vec4 v[MAX_BASES];
        filtered(pixel, p, v);
        for (uint j = 0u; j < BASES; ++j) {
            bases[basis_index(j, p)] = v[j];
            for (uint i = 0u; i <= j; ++i) gram[gram_index(i, j)] = dot(v[i].rgb, v[j].rgb);
        }
    }
    // Only for --ccipca-orthogonalize always (sum_vec4s > 0). Uniform over the dispatch, and
    // every invocation reaches the group's sum (it holds barriers).
    if (ccipca.sum_vec4s == 0u) return;
    vec4 s[SUM_VEC4S];
    for (uint m = 0u; m < SUM_VEC4S; ++m) s[m] = vec4(gram[4u * m], gram[4u * m + 1u], gram[4u * m + 2u], gram[4u * m + 3u]);
    store_partials(s, gram_vec4s(BASES));
}
