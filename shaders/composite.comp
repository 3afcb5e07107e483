#version 460
// Composite and tonemap: ambient x albedo x the product of the visibility terms, plus the
// radiance terms, Reinhard tonemap, sRGB encode. A bounce-and-modulation term's factor (a)
// darkens the ambient light and the direct radiance; its bounce (rgb) adds as irradiance. The
// effects' images arrive as numbered terms with a kind each (src/effects/effect.rs
// `TermKind`), so no effect combination needs a variant.
// With antialiasing (the `linear` permutation) the tonemapped colour is written display-linear
// to an fp32 image, which the antialiasing pass filters and encodes.
// @permutation srgb:
// @permutation linear: LINEAR_OUT
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "srgb.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The terms, fixed when the pipeline is built (specialization constants): how many, and the
// kind of each, so the driver compiles the unused fetches and branches away.
layout(constant_id = 0) const uint TERM_COUNT = 1u;
layout(constant_id = 1) const uint KIND0 = 0u;
layout(constant_id = 2) const uint KIND1 = 0u;
layout(constant_id = 3) const uint KIND2 = 0u;
layout(constant_id = 4) const uint KIND3 = 0u;

const uint TERM_RADIANCE = 0u;
const uint TERM_AMBIENT_VISIBILITY = 1u;
const uint TERM_VPL_IRRADIANCE = 2u;
const uint TERM_BOUNCE_MODULATION = 3u;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_albedo;
#ifdef LINEAR_OUT
layout(set = 1, binding = 2, rgba32f) uniform writeonly image2D out_color;
#else
layout(set = 1, binding = 2, rgba8) uniform writeonly image2D out_color;
#endif
layout(set = 1, binding = 3) uniform texture2D term0;
layout(set = 1, binding = 4) uniform texture2D term1;
layout(set = 1, binding = 5) uniform texture2D term2;
layout(set = 1, binding = 6) uniform texture2D term3;

// Ambient visibility factor of a term (1 unless it is a visibility term).
float visibility_of(uint kind, vec4 t) {
    return kind == TERM_AMBIENT_VISIBILITY ? t.r : 1.0;
}

// A bounce-and-modulation term's modulation factor (1 for other kinds).
float modulation_of(uint kind, vec4 t) {
    return kind == TERM_BOUNCE_MODULATION ? t.a : 1.0;
}

// Radiance a term adds for a receiver of albedo `albedo`.
vec3 radiance_of(uint kind, vec4 t, vec3 albedo, float modulation) {
    if (kind == TERM_RADIANCE) return t.rgb * modulation;
    if (kind == TERM_BOUNCE_MODULATION) return albedo / PI * t.rgb;
    // Eq 9 treats a VPL as emitting Phi cos / d^2; a diffuse emitter of flux Phi has intensity
    // Phi cos / pi, hence the 1/pi, and the receiver reflects albedo / pi of it.
    if (kind == TERM_VPL_IRRADIANCE) return albedo / PI * t.rgb / PI;
    return vec3(0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec3 color = vec3(0.0);
    // Through a variable: glslang would turn `TERM_COUNT > 1u` into OpSpecConstantOp, which
    // naga's reflection cannot read; the driver still folds it once specialized.
    uint count = TERM_COUNT;
    if (texelFetch(g_position, pixel, 0).w != 0.0) {
        vec3 albedo = texelFetch(g_albedo, pixel, 0).rgb;
        vec4 t0 = texelFetch(term0, pixel, 0);
        vec4 t1 = count > 1u ? texelFetch(term1, pixel, 0) : vec4(0.0);
        vec4 t2 = count > 2u ? texelFetch(term2, pixel, 0) : vec4(0.0);
        vec4 t3 = count > 3u ? texelFetch(term3, pixel, 0) : vec4(0.0);
        float m = modulation_of(KIND0, t0);
        if (count > 1u) m *= modulation_of(KIND1, t1);
        if (count > 2u) m *= modulation_of(KIND2, t2);
        if (count > 3u) m *= modulation_of(KIND3, t3);
        float visibility = visibility_of(KIND0, t0);
        if (count > 1u) visibility *= visibility_of(KIND1, t1);
        if (count > 2u) visibility *= visibility_of(KIND2, t2);
        if (count > 3u) visibility *= visibility_of(KIND3, t3);
        color = frame.ambient * albedo * visibility * m;
        color += radiance_of(KIND0, t0, albedo, m);
        if (count > 1u) color += radiance_of(KIND1, t1, albedo, m);
        if (count > 2u) color += radiance_of(KIND2, t2, albedo, m);
        if (count > 3u) color += radiance_of(KIND3, t3, albedo, m);
    }
    // Non-finite input must not reach the image as garbage: show it as black.
    if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0);
    color = color / (1.0 + color);
#ifdef LINEAR_OUT
    imageStore(out_color, pixel, vec4(clamp(color, 0.0, 1.0), 1.0));
#else
    imageStore(out_color, pixel, vec4(srgb_encode(clamp(color, 0.0, 1.0)), 1.0));
#endif
}
