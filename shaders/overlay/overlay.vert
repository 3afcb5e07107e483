#version 460
// The viewer's overlay (egui's tessellated meshes) over the presented frame: positions in
// egui points, mapped to clip space by the screen's size in points.
#extension GL_GOOGLE_include_directive : require
#include "overlay.glsl"

layout(location = 0) in vec2 in_position;
layout(location = 1) in vec2 in_uv;
layout(location = 2) in vec4 in_color; // sRGB-encoded, premultiplied (R8G8B8A8_UNORM)

layout(location = 0) out vec2 v_uv;
layout(location = 1) out vec4 v_color;

void main() {
    v_uv = in_uv;
    v_color = in_color;
    vec2 ndc = 2.0 * in_position / max(overlay.screen_points, vec2(1.0)) - 1.0;
    gl_Position = vec4(ndc, 0.0, 1.0);
}
