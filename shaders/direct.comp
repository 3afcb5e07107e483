#version 460
// Direct light from the spot light with percentage-closer filtered shadows (Reeves et al.
// 1987): k x k depth comparisons on a regular grid around the projected point, averaged.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D g_albedo;
layout(set = 1, binding = 3) uniform texture2D shadow_depth;
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D direct_out;

// Fraction of the PCF kernel that sees the light. `receiver` is the view-space distance of the
// point along the light axis; `bias` is in the same units.
float pcf_visibility(vec2 uv, float receiver, float bias) {
    int size = int(frame.light_params.z);
    int k = int(frame.size.w);
    float radius = frame.light_params.w;
    float lit = 0.0;
    for (int j = 0; j < k; ++j) {
        for (int i = 0; i < k; ++i) {
            vec2 offset = k > 1 ? (vec2(i, j) / float(k - 1) * 2.0 - 1.0) * radius : vec2(0.0);
            ivec2 texel = ivec2(floor(uv * float(size) + offset));
            // Outside the shadow map means outside the light frustum: unlit by the spot cone
            // anyway, count it as lit so the cone alone shapes the edge.
            if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) {
                lit += 1.0;
                continue;
            }
            float occluder = light_linear_depth(texelFetch(shadow_depth, texel, 0).r);
            lit += receiver <= occluder + bias ? 1.0 : 0.0;
        }
    }
    return lit / float(k * k);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), frame.size.xy))) return;
    vec4 position = texelFetch(g_position, pixel, 0);
    if (position.w == 0.0) { // background
        imageStore(direct_out, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    vec3 albedo = texelFetch(g_albedo, pixel, 0).rgb;

    vec3 to_light = frame.light_pos.xyz - p;
    // 1/d^2 with d^2 floored at the light's near^2 (as SpotLight::irradiance on the CPU): points
    // that close are outside the shadow frustum anyway, and the floor scales with the light.
    float near = frame.light_intensity.w;
    float dist2 = max(dot(to_light, to_light), max(near * near, 1e-30));
    vec3 l = safe_normalize(to_light, frame.light_dir.xyz);
    float cos_surface = max(dot(n, l), 0.0);
    vec3 irradiance = frame.light_intensity.rgb * spot_factor(-l) * cos_surface / dist2;

    float visibility = 0.0;
    if (cos_surface > 0.0 && any(greaterThan(irradiance, vec3(0.0)))) {
        vec4 clip = frame.light_view_proj * vec4(p, 1.0);
        float receiver = clip.w; // view-space distance along the light axis
        vec2 uv = clip.xy / max(clip.w, 1e-30) * 0.5 + 0.5;
        // Bias relative to the world size of one shadow texel at the receiver, grown with the
        // slope of the surface to the light: scale-free, as everything is proportional to depth.
        float texel_world = 2.0 * receiver * frame.light_params.y / frame.light_params.z;
        float slope = sqrt(max(1.0 - cos_surface * cos_surface, 0.0)) / max(cos_surface, 0.1);
        float bias = texel_world * (1.0 + min(slope, 10.0)) + 1e-5 * receiver;
        visibility = pcf_visibility(uv, receiver, bias);
    }
    vec3 radiance = albedo / PI * irradiance * visibility;
    imageStore(direct_out, pixel, vec4(radiance, visibility));
}
