#version 460
// Direct light from the spot light, times the shadow visibility computed by the shadow pass
// (PCF every frame, or accumulated with the cache).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D g_albedo;
layout(set = 1, binding = 3) uniform texture2D shadow_visibility; // r = PCF visibility
layout(set = 1, binding = 4, rgba16f) uniform writeonly image2D direct_out;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 position = texelFetch(g_position, pixel, 0);
    if (position.w == 0.0) { // background
        imageStore(direct_out, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    vec3 albedo = texelFetch(g_albedo, pixel, 0).rgb;

    vec3 to_light = frame.light_pos - p;
    // 1/d^2 with d^2 floored at the light's near^2 (as SpotLight::irradiance on the CPU): points
    // that close are outside the shadow frustum anyway, and the floor scales with the light.
    float near = frame.light_near;
    float dist2 = max(dot(to_light, to_light), max(near * near, 1e-30));
    vec3 l = safe_normalize(to_light, frame.light_dir);
    float cos_surface = max(dot(n, l), 0.0);
    vec3 irradiance = frame.light_intensity * spot_factor(-l) * cos_surface / dist2;
    float visibility = cos_surface > 0.0 ? texelFetch(shadow_visibility, pixel, 0).r : 0.0;
    vec3 radiance = albedo / PI * irradiance * visibility;
    imageStore(direct_out, pixel, vec4(radiance, visibility));
}
