#version 460
// G-buffer MRT: world position (w = 1 marks geometry), world normal, albedo.
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
layout(location = 2) out vec4 out_albedo;

void main() {
    vec3 to_eye = frame.camera_pos - v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(to_eye, vec3(0.0, 1.0, 0.0)));
    // Two-sided surfaces: OBJ winding is unreliable, so the side seen is decided per triangle:
    // the geometric normal (from the position's screen derivatives, constant over the
    // triangle) turned to the eye. The vertex normals are flipped when they point to the
    // triangle's other side. Testing the interpolated normal against the eye instead flipped
    // it wherever a smooth normal turns away near a silhouette, so one surface point's normal
    // (and everything computed from it: AO, indirect light) changed with the view, and a
    // history computed there stayed wrong after the view moved on. A degenerate triangle
    // (zero derivatives) falls back to the eye test.
    vec3 ng = cross(dFdx(v_position), dFdy(v_position));
    float side = dot(ng, ng) > 0.0 ? dot(n, ng) * sign(dot(ng, to_eye)) : dot(n, to_eye);
    if (side < 0.0) n = -n;
    vec3 albedo = material.albedo.rgb;
#ifdef TEXTURED
    albedo *= texture(sampler2D(diffuse_texture, diffuse_sampler), v_uv).rgb;
#endif
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
    out_albedo = vec4(albedo, 1.0);
}
