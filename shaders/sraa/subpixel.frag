#version 460
// SRAA's subpixel geometry (one render per subpixel offset): world position (w = 1 marks
// geometry) and the normal of the side the eye sees, as the G-buffer writes them, so the
// reconstruction compares like with like. No material: shading is never computed here.
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"
#include "two_sided.glsl"

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec3 v_prev_position; // unused here (the G-buffer's motion)

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;

void main() {
    vec3 to_eye = frame.camera_pos - v_position;
    vec3 n = safe_normalize(v_normal, safe_normalize(to_eye, vec3(0.0, 1.0, 0.0)));
    n = visible_side(n, v_position, frame.camera_pos);
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
}
