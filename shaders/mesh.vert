#version 460
// Shared vertex stage of the two raster passes: G-buffer (camera) and light view (RSM).
// @permutation camera: VIEW_CAMERA
// @permutation light: VIEW_LIGHT
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 v_position;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec2 v_uv;

void main() {
    v_position = in_position;
    v_normal = in_normal;
    v_uv = in_uv;
#ifdef VIEW_LIGHT
    gl_Position = frame.light_view_proj * vec4(in_position, 1.0);
#else
    gl_Position = frame.view_proj * vec4(in_position, 1.0);
#endif
}
