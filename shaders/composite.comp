#version 460
// Composite and tonemap: ambient x albedo x the product of the visibility terms, plus the
// radiance terms, Reinhard tonemap, sRGB encode. The effects' images arrive as numbered terms
// with a kind each (src/effects/mod.rs `TermKind`), so no effect combination needs a variant.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// build.rs generates the Rust struct `CompositePush` from this block.
layout(push_constant) uniform Composite {
    uvec4 term_kinds; // per term: 0 radiance, 1 ambient visibility (r), 2 VPL irradiance (eq 9)
    uint term_count;
} composite;

const uint TERM_RADIANCE = 0u;
const uint TERM_AMBIENT_VISIBILITY = 1u;
const uint TERM_VPL_IRRADIANCE = 2u;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_albedo;
layout(set = 1, binding = 2, rgba8) uniform writeonly image2D out_color;
layout(set = 1, binding = 3) uniform texture2D term0;
layout(set = 1, binding = 4) uniform texture2D term1;
layout(set = 1, binding = 5) uniform texture2D term2;
layout(set = 1, binding = 6) uniform texture2D term3;

vec4 fetch_term(uint i, ivec2 pixel) {
    switch (i) {
    case 0u: return texelFetch(term0, pixel, 0);
    case 1u: return texelFetch(term1, pixel, 0);
    case 2u: return texelFetch(term2, pixel, 0);
    default: return texelFetch(term3, pixel, 0);
    }
}

vec3 srgb_encode(vec3 linear) {
    vec3 lo = linear * 12.92;
    vec3 hi = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(linear, vec3(0.0031308)));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 color = vec3(0.0);
    uint count = min(composite.term_count, 4u);
    if (texelFetch(g_position, pixel, 0).w != 0.0) {
        vec3 albedo = texelFetch(g_albedo, pixel, 0).rgb;
        float visibility = 1.0;
        for (uint i = 0u; i < count; ++i) {
            if (composite.term_kinds[i] == TERM_AMBIENT_VISIBILITY)
                visibility *= fetch_term(i, pixel).r;
        }
        color = frame.ambient * albedo * visibility;
        for (uint i = 0u; i < count; ++i) {
            uint kind = composite.term_kinds[i];
            if (kind == TERM_RADIANCE) {
                color += fetch_term(i, pixel).rgb;
            } else if (kind == TERM_VPL_IRRADIANCE) {
                // Eq 9 treats a VPL as emitting Phi cos / d^2; a diffuse emitter of flux Phi
                // has intensity Phi cos / pi, hence the 1/pi, and the receiver reflects
                // albedo / pi of it.
                color += albedo / PI * fetch_term(i, pixel).rgb / PI;
            }
        }
    }
    // Non-finite input must not reach the image as garbage: show it as black.
    if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0);
    color = color / (1.0 + color);
    imageStore(out_color, pixel, vec4(srgb_encode(clamp(color, 0.0, 1.0)), 1.0));
}
