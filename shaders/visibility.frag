#version 460
// Visibility buffer (--gbuffer visibility): each pixel's triangle, 1 + its index in the scene's
// index buffer / 3 (0 is the background), for gbuffer_resolve.comp to rebuild the G-buffer
// from. In a scene with textures the albedo is written here too: the texture's level comes
// from the rasterizer's derivatives, which a compute pass would have to rebuild.
// @permutation ids:
// @permutation flat: ALBEDO
// @permutation textured: ALBEDO TEXTURED
#extension GL_GOOGLE_include_directive : require
#include "material.glsl"

#ifdef TEXTURED
layout(set = 1, binding = 0) uniform texture2D diffuse_texture;
layout(set = 1, binding = 1) uniform sampler diffuse_sampler;
#endif

#ifdef TEXTURED
layout(location = 2) in vec2 v_uv;
#endif
layout(location = 4) flat in uint v_first_triangle;

layout(location = 0) out uint out_triangle;
#ifdef ALBEDO
layout(location = 1) out vec4 out_albedo;
#endif

void main() {
    out_triangle = v_first_triangle + uint(gl_PrimitiveID) + 1u;
#ifdef ALBEDO
    vec3 albedo = material.albedo.rgb;
#ifdef TEXTURED
    albedo *= texture(sampler2D(diffuse_texture, diffuse_sampler), v_uv).rgb;
#endif
    out_albedo = vec4(albedo, 1.0);
#endif
}
