#version 460
// Shared vertex stage of the raster passes: G-buffer (camera), light view (RSM), and the
// antialiasing's subpixel geometry (the camera shifted by a subpixel offset, chosen by the draw's instance).
// Each draw places its object in the world (material.glsl: the identity for static geometry)
// and hands on where the point was last frame.
// @permutation camera: VIEW_CAMERA
// @permutation light: VIEW_LIGHT
// @permutation subpixel: VIEW_CAMERA SUBPIXEL
// @permutation visibility: VIEW_CAMERA VISIBILITY
// @permutation visibility_uv: VIEW_CAMERA VISIBILITY VISIBILITY_UV
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"
#include "subpixel.glsl"
#include "material.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

#ifndef VISIBILITY
layout(location = 0) out vec3 v_position;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec2 v_uv;
layout(location = 3) out vec3 v_prev_position; // the G-buffer's motion: where it was
#else
// The visibility buffer (visibility.frag) takes only the triangle's numbering: the draw's
// first triangle in the scene's index buffer, passed as the draw's firstInstance
// (gl_PrimitiveID counts from the draw's start); and the texture coordinate where a material
// samples its texture.
layout(location = 4) flat out uint v_first_triangle;
#ifdef VISIBILITY_UV
layout(location = 2) out vec2 v_uv;
#endif
#endif

void main() {
    vec3 position = place(in_position);
#ifndef VISIBILITY
    v_position = position;
    v_prev_position = place_prev(in_position);
    v_normal = place_direction(in_normal);
    v_uv = in_uv;
#else
    v_first_triangle = uint(gl_InstanceIndex);
#ifdef VISIBILITY_UV
    v_uv = in_uv;
#endif
#endif
#ifdef VIEW_LIGHT
    gl_Position = frame.light_view_proj * vec4(position, 1.0);
#else
    gl_Position = frame.view_proj * vec4(position, 1.0);
#endif
#ifdef SUBPIXEL
    // The pixel centre samples what lies `offset` away from it once the image moves by
    // -offset: 2 / size per pixel in NDC, times w before the divide. gl_InstanceIndex is the
    // draw's firstInstance: the subpixel's index.
    vec2 offset = SUBPIXEL_OFFSETS[gl_InstanceIndex & 3];
    gl_Position.xy -= offset * 2.0 / vec2(frame.size) * gl_Position.w;
#endif
}
