#version 460
// SSDO (Szentandrasi sections 3.2 and 4.1). `one_step`: the modulation factor and the bounce in
// one pass, the bounce's senders lit as the frame is without SSDO (direct light + ambient x
// albedo) and the bounce darkened by the modulation factor. The original two steps:
// `directional` writes the directionally occluded lighting (direct + ambient x albedo, times
// the modulation factor; a = the factor), then `bounce` gathers the same samples' senders
// from that image. Output: rgb = bounce irradiance, a = modulation factor. At 1/scale
// resolution (--ssdo-scale 0.5) texel t shades the G-buffer's pixel t * scale, the samples still
// project to full-resolution pixels, and each texel keeps its own Halton shift. `ssao`: section
// 3.1's SSAO with the same samples, the unoccluded fraction in all four channels (the
// composite darkens only the ambient light with it, as with AO).
// @permutation one_step: ONE_STEP
// @permutation directional: DIRECTIONAL
// @permutation bounce: BOUNCE
// @permutation ssao: SSAO
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "ssdo_params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D g_albedo;
#ifdef BOUNCE
// The directional step's output: the senders' radiance, a = the pixel's modulation factor.
layout(set = 1, binding = 4) uniform texture2D lit;
#else
// The direct effect's outgoing radiance (read when ssdo.direct_enabled).
layout(set = 1, binding = 3) uniform texture2D direct_light;
#endif
// The pre-pass's samples per block (read when ssdo.threshold_count > 0).
layout(set = 1, binding = 6) uniform utexture2D block_samples;
#ifdef DIRECTIONAL
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D lit_out;
#else
layout(set = 1, binding = 5, rgba16f) uniform writeonly image2D ssdo_out;
// The pass that finishes SSDO counts its pixels and samples (computed_pixels, samples), summed
// per workgroup first so the buffer sees one atomic per group.
#define COUNTERS_BINDING 7
#include "counters.glsl"
shared uint group_pixels;
shared uint group_samples;
#endif

#ifdef BOUNCE
// `lit` is at SSDO's resolution: the texel covering full-resolution pixel q.
vec3 sender_radiance(ivec2 q) {
    return texelFetch(lit, q / int(ssdo.scale), 0).rgb;
}
#else
// The pixel lit as the frame is without SSDO: the direct light and the ambient it reflects.
vec3 sender_radiance(ivec2 q) {
    vec3 l = frame.ambient * texelFetch(g_albedo, q, 0).rgb;
    if (ssdo.direct_enabled != 0u) l += texelFetch(direct_light, q, 0).rgb;
    return l;
}
#endif

#include "ssdo.glsl"

#ifdef DIRECTIONAL
#define SSDO_OUT lit_out
#else
#define SSDO_OUT ssdo_out
#endif

// Shades one texel; returns the samples it took (0 for background).
uint shade(ivec2 texel) {
    ivec2 pixel = texel * int(ssdo.scale);
    vec4 position = texelFetch(g_position, pixel, 0);
    vec4 result = vec4(0.0, 0.0, 0.0, 1.0);
    uint count = 0u;
    if (position.w != 0.0) {
        vec3 n = texelFetch(g_normal, pixel, 0).xyz;
        count = ssdo.samples;
        if (ssdo.threshold_count > 0u)
            count = texelFetch(block_samples, pixel / int(ssdo.prepass_scale), 0).r;
        // The same K samples every frame (Halton indices 0 .. K - 1, shifted per pixel).
        uint first = 0u;
#ifdef DIRECTIONAL
        float m = ssdo_pixel(g_position, g_normal, texel, position.xyz, n, first, count, count, false).a;
        result = vec4(sender_radiance(pixel) * m, m);
#elif defined(BOUNCE)
        vec3 e = ssdo_pixel(g_position, g_normal, texel, position.xyz, n, first, count, count, true).rgb;
        result = vec4(e, texelFetch(lit, texel, 0).a);
#elif defined(SSAO)
        result = vec4(ssao_pixel(g_position, g_normal, texel, position.xyz, n, first, count));
#else
        result = ssdo_pixel(g_position, g_normal, texel, position.xyz, n, first, count, count, true);
        result.rgb *= result.a;
#endif
    }
    imageStore(SSDO_OUT, texel, result);
    return count;
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(texel, imageSize(SSDO_OUT)));
#ifdef DIRECTIONAL
    if (inside) shade(texel);
#else
    if (gl_LocalInvocationIndex == 0u) {
        group_pixels = 0u;
        group_samples = 0u;
    }
    barrier();
    uint count = inside ? shade(texel) : 0u;
    if (count > 0u) {
        atomicAdd(group_pixels, 1u);
        atomicAdd(group_samples, count);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_pixels > 0u) {
        atomicAdd(counters.computed_pixels, group_pixels);
        atomicAdd(counters.samples, group_samples);
    }
#endif
}
