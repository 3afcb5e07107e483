#version 460
// Reflective shadow map MRT (Dachsbacher & Stamminger 2005): world position, normal and the
// flux each texel reflects. The depth attachment of the same pass is the shadow map.
// @permutation flat: 
// @permutation textured: TEXTURED
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(push_constant) uniform Material {
    vec4 albedo;
} material;

#ifdef TEXTURED
layout(set = 1, binding = 0) uniform texture2D diffuse_texture;
layout(set = 1, binding = 1) uniform sampler diffuse_sampler;
#endif

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_flux;

void main() {
    vec3 to_light = frame.light_pos - v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(to_light, vec3(0.0, 1.0, 0.0)));
    if (dot(n, to_light) < 0.0) n = -n; // the lit side is the side facing the light
    vec3 albedo = material.albedo.rgb;
#ifdef TEXTURED
    albedo *= texture(sampler2D(diffuse_texture, diffuse_sampler), v_uv).rgb;
#endif
    // Flux through this texel: I(w) times the texel's solid angle. On the image plane at unit
    // distance a texel has area (2 tan(fov/2) / N)^2; seen off-axis at angle t it subtends
    // that area times cos^3(t). All of it lands on this surface, which reflects albedo of it.
    vec3 dir = safe_normalize(-to_light, frame.light_dir);
    float cos_axis = max(dot(dir, frame.light_dir), 0.0);
    float texel = 2.0 * frame.light_tan_half_fov / frame.shadow_map_size;
    float solid_angle = texel * texel * cos_axis * cos_axis * cos_axis;
    vec3 flux = albedo * frame.light_intensity * spot_factor(dir) * solid_angle;
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
    out_flux = vec4(flux, 1.0);
}
