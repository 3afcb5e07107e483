#version 460
// Composite and tonemap: direct light plus ambient x albedo (x AO visibility), Reinhard
// tonemap, sRGB encode. Permutations leave out the inputs of disabled effects.
// @permutation d: USE_DIRECT
// @permutation a: USE_AO
// @permutation i: USE_INDIRECT
// @permutation da: USE_DIRECT USE_AO
// @permutation di: USE_DIRECT USE_INDIRECT
// @permutation ai: USE_AO USE_INDIRECT
// @permutation dai: USE_DIRECT USE_AO USE_INDIRECT
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_albedo;
layout(set = 1, binding = 2, rgba8) uniform writeonly image2D out_color;
#ifdef USE_DIRECT
layout(set = 1, binding = 3) uniform texture2D direct_light;
#endif
#ifdef USE_AO
layout(set = 1, binding = 4) uniform texture2D ambient_visibility; // r = 1 - occlusion
#endif
#ifdef USE_INDIRECT
layout(set = 1, binding = 5) uniform texture2D indirect_light; // rgb = eq 9's I_p
#endif

vec3 srgb_encode(vec3 linear) {
    vec3 lo = linear * 12.92;
    vec3 hi = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(linear, vec3(0.0031308)));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size))) return;
    vec3 color = vec3(0.0);
    if (texelFetch(g_position, pixel, 0).w != 0.0) {
        vec3 albedo = texelFetch(g_albedo, pixel, 0).rgb;
        float visibility = 1.0;
#ifdef USE_AO
        visibility = texelFetch(ambient_visibility, pixel, 0).r;
#endif
        color = frame.ambient * albedo * visibility;
#ifdef USE_DIRECT
        color += texelFetch(direct_light, pixel, 0).rgb;
#endif
#ifdef USE_INDIRECT
        // Eq 9 treats a VPL as emitting Phi cos / d^2; a diffuse emitter of flux Phi has
        // intensity Phi cos / pi, hence the 1/pi, and the receiver reflects albedo / pi of it.
        color += albedo / PI * texelFetch(indirect_light, pixel, 0).rgb / PI;
#endif
    }
    // Non-finite input must not reach the image as garbage: show it as black.
    if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0);
    color = color / (1.0 + color);
    imageStore(out_color, pixel, vec4(srgb_encode(clamp(color, 0.0, 1.0)), 1.0));
}
