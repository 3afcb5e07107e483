// Screen-space directional occlusion (Szentandrasi section 3.2, Ritschel et al. 2009) with this
// renderer's lights. The G-buffer it reads is a parameter; what a sender emits is the includer's
// `sender_radiance(pixel)`, defined before inclusion (this frame's direct light, or the
// reprojected last frame's: the two passes differ there).
#ifndef SSDO_GLSL
#define SSDO_GLSL

#include "frame.glsl"
#include "ssdo_params.glsl"
#include "hemisphere.glsl"

// Exponent of the lobe the spot light's radiance is spread over (see ssdo_incident): a cosine
// power of 8 falls to half at 22 degrees from the light's direction, wide enough that 10
// hemisphere samples see it, narrow enough that occluders towards the light count most.
const float SSDO_LIGHT_LOBE = 8.0;

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// L_in of eq 2 for direction omega at p, as a luminance: the ambient term is a uniform
// environment of radiance `ambient`; the spot light (the paper's point-light case, section
// 4.1) delivers the irradiance E = I spot(l) / d^2 normal to its direction l, spread over a
// normalised cosine-power lobe around l ((m + 1) / (2 pi) max(omega . l, 0)^m integrates to 1
// over the sphere), because a delta direction would never be drawn by K samples. Shadows from
// the shadow map stay in the direct light; this only weighs which directions matter.
float ssdo_incident(vec3 p, vec3 omega) {
    vec3 to_light = frame.light_pos - p;
    float near = frame.light_near;
    float dist2 = max(dot(to_light, to_light), max(near * near, 1e-30));
    vec3 l = safe_normalize(to_light, frame.light_dir);
    float e = luminance(frame.light_intensity) * spot_factor(-l) / dist2;
    float lobe = (SSDO_LIGHT_LOBE + 1.0) / TWO_PI * pow(max(dot(omega, l), 0.0), SSDO_LIGHT_LOBE);
    return luminance(frame.ambient) + e * lobe;
}

// One pixel's SSDO: the modulation factor of section 4.1 (eq 2 with visibility over eq 2
// without, with the same samples) and eq 4's bounce as irradiance (the composite multiplies by
// albedo / pi). The senders are the visible surfaces where occluded samples project (Figure
// 2's A and D), each a patch of area A_s = pi r_max^2 / K facing the receiver (back-facing
// ones, N_s . (P - P_s) <= 0, send nothing), with the cosines taken along the actual segment
// P_s - P. Eq 4 as printed also multiplies by delta omega; A_s cos / d^2 is already the
// patch's solid angle, so that factor is left out, as in Ritschel et al.'s eq. d^2 is floored
// at A_s / (2 pi), where the patch would subtend a whole hemisphere: scale-free, since A_s
// scales with r_max^2. The floor takes the patch of the estimate's whole sample set,
// `floor_count` samples: K for one pass; with the cache, which averages patterns of K samples
// into one estimate of K times the rotation limit, that many, so the accumulated bounce
// converges to the many-sample one rather than to a K-sample floor's (36x larger at K = 10).
// `texel` (SSDO's grid) picks the Halton shift. Returns (bounce rgb, modulation).
vec4 ssdo_pixel(texture2D position, texture2D normals, ivec2 texel, vec3 p, vec3 n,
                uint first_sample, uint count, uint floor_count, bool bounce) {
    float r_max = ssdo.radius * frame.scene_radius;
    float area = PI * r_max * r_max / float(max(count, 1u));
    float d2_floor = PI * r_max * r_max / float(max(floor_count, 1u)) / TWO_PI;
    float lit = 0.0;
    float unoccluded = 0.0;
    vec3 e_bounce = vec3(0.0);
    for (uint k = 0u; k < count; ++k) {
        vec4 w = hemisphere_sample(first_sample + k, texel, n, r_max);
        HemisphereTap tap = hemisphere_tap(position, normals, p + w.w * w.xyz, r_max);
        float weight = ssdo_incident(p, w.xyz) * max(dot(n, w.xyz), 0.0);
        unoccluded += weight;
        if (!tap.occluded) {
            lit += weight;
            continue;
        }
        if (!bounce) continue;
        vec3 to_receiver = p - tap.q;
        float d2 = dot(to_receiver, to_receiver);
        vec3 dir = safe_normalize(to_receiver, n);
        float cos_sender = dot(tap.q_normal, dir);
        float cos_receiver = dot(n, -dir);
        if (cos_sender <= 0.0 || cos_receiver <= 0.0) continue;
        e_bounce += sender_radiance(tap.q_pixel) * (area * cos_sender * cos_receiver / max(d2, d2_floor));
    }
    float modulation = unoccluded > 0.0 ? lit / unoccluded : 1.0;
    return vec4(e_bounce, modulation);
}

// Section 3.1's SSAO with the same samples: the fraction of the `count` points from Halton index
// `first_sample` that are not occluded.
float ssao_pixel(texture2D position, texture2D normals, ivec2 texel, vec3 p, vec3 n,
                 uint first_sample, uint count) {
    float r_max = ssdo.radius * frame.scene_radius;
    float occluded = 0.0;
    for (uint k = 0u; k < count; ++k) {
        vec4 w = hemisphere_sample(first_sample + k, texel, n, r_max);
        if (hemisphere_tap(position, normals, p + w.w * w.xyz, r_max).occluded) occluded += 1.0;
    }
    return 1.0 - occluded / float(max(count, 1u));
}

#endif // SSDO_GLSL
