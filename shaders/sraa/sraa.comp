#version 460
// Subpixel reconstruction antialiasing (Chajdas et al. 2011, as extended by Chiu et al.): each
// pixel was shaded once (the composite, at the G-buffer's pixel centre); its four subpixels
// (the rotated grid of subpixel.glsl, rendered geometry only) each rebuild their shading from
// the shaded pixels around them with eq 1's bilateral weights, and the pixel is the box
// filter of its four subpixels. With `sraa.sigma_shadow` > 0 a hard shadow-map test at
// every sample joins the weight (the report's section 3.2), so shading does not cross shadow
// edges, which the eye's geometry cannot see.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "srgb.glsl"
#include "subpixel.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Eq 1's weights (post/sraa/config.rs). build.rs generates the Rust struct `SraaPush`.
layout(push_constant) uniform Sraa {
    float sigma_z;      // scale on the relative eye-distance difference
    float sigma_n;      // scale on 1 - sat(n_j . n_i)
    float sigma_shadow; // scale on the shadow tests' difference (0 = no term)
} sraa;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
// The composite's image: display-linear colour (tonemapped, not yet sRGB-encoded).
layout(set = 1, binding = 2) uniform texture2D shaded;
layout(set = 1, binding = 3) uniform texture2D shadow_depth;
layout(set = 1, binding = 4) uniform texture2D sub_position0;
layout(set = 1, binding = 5) uniform texture2D sub_position1;
layout(set = 1, binding = 6) uniform texture2D sub_position2;
layout(set = 1, binding = 7) uniform texture2D sub_position3;
layout(set = 1, binding = 8) uniform texture2D sub_normal0;
layout(set = 1, binding = 9) uniform texture2D sub_normal1;
layout(set = 1, binding = 10) uniform texture2D sub_normal2;
layout(set = 1, binding = 11) uniform texture2D sub_normal3;
layout(set = 1, binding = 12, rgba8) uniform writeonly image2D out_color;

#include "shadow.glsl"

// Spatial weight's floor: a shaded pixel of the 3x3 neighbourhood outside the subpixel's
// bilinear footprint still counts this much, so a subpixel whose surface none of its four
// nearest pixel centres saw takes its shading from any neighbour on that surface. Small
// against the footprint's weights (which sum to 1), so it cannot blur a surface all nine share.
const float SPATIAL_FLOOR = 1e-4;

// A pixel whose four subpixels all weigh at least this against its own shaded sample has no
// edge inside it. Eq 1's weights are near 1 on one surface (a 1% eye-distance difference is
// 0.99) and near 0 across a depth edge (10% is 1/e, 20% 0.02), so the split is not delicate.
const float EDGE_WEIGHT = 0.5;

struct Sample {
    vec3 n;
    // Distance from the eye; 0 marks background (no geometry).
    float dist;
    // Hard shadow-map visibility (0 or 1), only with the shadow term.
    float lit;
};

float gauss(float x) {
    return exp(-x * x);
}

Sample sample_at(vec4 position, vec4 normal) {
    Sample s;
    s.n = normal.xyz;
    s.dist = position.w != 0.0 ? max(length(position.xyz - frame.camera_pos), 1e-30) : 0.0;
    s.lit = 1.0;
    if (position.w != 0.0 && sraa.sigma_shadow > 0.0) {
        vec3 l = safe_normalize(frame.light_pos - position.xyz, -frame.light_dir);
        float cos_surface = dot(s.n, l);
        s.lit = cos_surface > 0.0
            ? shadow_test(light_receiver(position.xyz, s.n, cos_surface), vec2(0.0))
            : 0.0;
    }
    return s;
}

// Eq 1 between subpixel i and shaded sample j: G(sz dz) G(sn (1 - sat(n_j . n_i))), times
// G(ss (lit_j - lit_i)) with the shadow term. dz is the relative difference of the distances
// from the eye, (z_j - z_i) / max(z_i, z_j): scale-free (a scene scaled by any factor weighs
// the same) and within [-1, 1], so sz = 10 (the paper's value) puts a neighbour 10% nearer or
// farther at weight 1/e. Background only matches background.
float weight(Sample i, Sample j) {
    bool gi = i.dist > 0.0;
    bool gj = j.dist > 0.0;
    if (gi != gj) return 0.0;
    if (!gi) return 1.0;
    float dz = (j.dist - i.dist) / max(i.dist, j.dist);
    float w = gauss(sraa.sigma_z * dz)
        * gauss(sraa.sigma_n * (1.0 - clamp(dot(j.n, i.n), 0.0, 1.0)));
    if (sraa.sigma_shadow > 0.0) w *= gauss(sraa.sigma_shadow * (j.lit - i.lit));
    return w;
}

vec4 sub_position(int s, ivec2 p) {
    if (s == 0) return texelFetch(sub_position0, p, 0);
    if (s == 1) return texelFetch(sub_position1, p, 0);
    if (s == 2) return texelFetch(sub_position2, p, 0);
    return texelFetch(sub_position3, p, 0);
}

vec4 sub_normal(int s, ivec2 p) {
    if (s == 0) return texelFetch(sub_normal0, p, 0);
    if (s == 1) return texelFetch(sub_normal1, p, 0);
    if (s == 2) return texelFetch(sub_normal2, p, 0);
    return texelFetch(sub_normal3, p, 0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    Sample sub[4];
    for (int s = 0; s < 4; ++s) sub[s] = sample_at(sub_position(s, pixel), sub_normal(s, pixel));
    // No edge (geometric, or with the shadow term a shadow edge) inside the pixel: every
    // subpixel matches the pixel's own shaded sample, which it keeps as it is (the
    // reconstruction would only blur smooth shading).
    Sample own = sample_at(texelFetch(g_position, pixel, 0), texelFetch(g_normal, pixel, 0));
    vec3 own_color = texelFetch(shaded, pixel, 0).rgb;
    float match = 1.0;
    for (int s = 0; s < 4; ++s) match = min(match, weight(sub[s], own));
    vec3 color = own_color;
    if (match < EDGE_WEIGHT) {
        vec3 sum[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
        float total[4] = float[4](0.0, 0.0, 0.0, 0.0);
        // The shaded pixels within one pixel (3x3): each is loaded and shadow-tested once and
        // serves the four subpixels.
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = pixel + ivec2(dx, dy);
                if (outside_frame(q)) continue;
                bool centre = dx == 0 && dy == 0;
                Sample j = centre ? own
                    : sample_at(texelFetch(g_position, q, 0), texelFetch(g_normal, q, 0));
                vec3 c = centre ? own_color : texelFetch(shaded, q, 0).rgb;
                for (int s = 0; s < 4; ++s) {
                    // Bilinear footprint of the subpixel over the pixel centres around it.
                    vec2 d = abs(SUBPIXEL_OFFSETS[s] - vec2(dx, dy));
                    float spatial = max(1.0 - d.x, 0.0) * max(1.0 - d.y, 0.0) + SPATIAL_FLOOR;
                    float w = spatial * weight(sub[s], j);
                    sum[s] += w * c;
                    total[s] += w;
                }
            }
        }
        color = vec3(0.0);
        // A subpixel no neighbour matches (every weight underflowed) keeps the pixel's own
        // shading.
        for (int s = 0; s < 4; ++s) color += total[s] > 0.0 ? sum[s] / total[s] : own_color;
        color *= 0.25;
    }
    if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0);
    imageStore(out_color, pixel, vec4(srgb_encode(clamp(color, 0.0, 1.0)), 1.0));
}
