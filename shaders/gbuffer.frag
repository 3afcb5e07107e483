#version 460
// G-buffer MRT: world position (w = 1 marks geometry), world normal, albedo, and motion: how
// far the surface point moved in the world since last frame (0 for what stands still), so the
// reprojection finds where a moving object's pixel was.
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
layout(location = 3) in vec3 v_prev_position;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec4 out_motion;

void main() {
    vec3 to_eye = frame.camera_pos - v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(to_eye, vec3(0.0, 1.0, 0.0)));
    // The side the eye sees, per triangle: a view-dependent normal would leave AO and indirect
    // histories computed near a silhouette wrong after the view moves on.
    n = visible_side(n, v_position, frame.camera_pos);
    vec3 albedo = material.albedo.rgb;
#ifdef TEXTURED
    albedo *= texture(sampler2D(diffuse_texture, diffuse_sampler), v_uv).rgb;
#endif
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
    out_albedo = vec4(albedo, 1.0);
    // Both points are interpolated alike: exactly 0 where the transforms are equal.
    out_motion = vec4(v_position - v_prev_position, 0.0);
}
