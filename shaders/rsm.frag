#version 460
// Reflective shadow map MRT (Dachsbacher & Stamminger 2005): world position, normal and the
// flux each texel reflects, stored per unit solid angle and before the cone falloff (see
// below). The depth attachment of the same pass is the shadow map.
// @permutation flat: 
// @permutation textured: TEXTURED
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"
#include "two_sided.glsl"

#include "material.glsl"

#ifdef TEXTURED
layout(set = 1, binding = 0) uniform texture2D diffuse_texture;
layout(set = 1, binding = 1) uniform sampler diffuse_sampler;
#endif

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec3 v_prev_position; // unused here (the G-buffer's motion)

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_flux;

void main() {
    vec3 to_light = frame.light_pos - v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(to_light, vec3(0.0, 1.0, 0.0)));
    n = visible_side(n, v_position, frame.light_pos); // the lit side, per triangle
    vec3 albedo = material.albedo.rgb;
#ifdef TEXTURED
    albedo *= texture(sampler2D(diffuse_texture, diffuse_sampler), v_uv).rgb;
#endif
    // The flux this texel reflects is albedo x I x spot factor x the texel's solid angle
    // (vpl_flux in rsm_gather.glsl). The target is fp16, whose normal range ends at 6.1e-5:
    // the solid angle scales as 1/N^2 (3.5e-5 at the Cornell cone's edge with N = 512) and
    // the spot factor runs to 0 at the cone's edge, so the full product would be subnormal or
    // zero on large maps. Stored is albedo x I [W/sr], whose magnitude does not depend on N or
    // on the cone; the gather multiplies the two factors back in fp32.
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
    out_flux = vec4(albedo * frame.light_intensity, 1.0);
}
