#version 460
// Visibility-buffer G-buffer (--gbuffer visibility): the raster pass wrote only each pixel's
// triangle (visibility.frag); here every pixel rebuilds what gbuffer.frag writes (world
// position, the visible side's normal, albedo, motion) from its triangle's vertices. Raster
// output on some GPUs is the frame's bottleneck (the H200 wrote the 40-byte G-buffer at about
// 20 GB/s: its cost followed the bytes per pixel); a 4-byte raster target and a compute pass
// on every core move that work where the GPU is wide.
//
// The weights are the perspective-correct barycentrics of the pixel centre, from clip-space
// homogeneous coordinates (Olano and Greer 1997): the point C = sum b_i c_i of the triangle
// that projects onto ndc q satisfies sum b_i (x_i - q.x w_i) = 0 and sum b_i (y_i - q.y w_i)
// = 0, so b is the cross product of those two rows, scaled to sum 1. No vertex is divided by
// its w, so triangles crossing the eye plane need no clipping.
// @permutation flat:
// @permutation textured: TEXTURED_SCENE
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#define TWO_SIDED_NO_DERIVATIVES
#include "two_sided.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0, r32ui) uniform readonly uimage2D visibility;
// The scene's vertices: position xyz, normal xyz, uv (8 floats: raster.rs's VERTEX_ATTRIBUTES).
layout(set = 1, binding = 1, std430) readonly buffer Vertices { float vertex_data[]; };
layout(set = 1, binding = 2, std430) readonly buffer Indices { uint index_data[]; };
// The draw each triangle belongs to.
layout(set = 1, binding = 3, std430) readonly buffer TriangleDraws { uint triangle_draw[]; };
// Per draw, material.glsl's push block: albedo, this frame's and last frame's object -> world
// rows. One table per frame slot (push constant `table_base` picks it).
struct DrawEntry {
    vec4 albedo;
    vec4 model_x;
    vec4 model_y;
    vec4 model_z;
    vec4 prev_model_x;
    vec4 prev_model_y;
    vec4 prev_model_z;
};
layout(set = 1, binding = 4, std430) readonly buffer Draws { DrawEntry draws[]; };
layout(set = 1, binding = 5, rgba32f) uniform writeonly image2D out_position;
layout(set = 1, binding = 6, rgba16f) uniform writeonly image2D out_normal;
layout(set = 1, binding = 7, rgba16f) uniform writeonly image2D out_motion;
#ifndef TEXTURED_SCENE
// In a scene with textures the raster pass writes albedo (it samples the texture with the
// derivatives the rasterizer has); without, albedo is the draw's colour.
layout(set = 1, binding = 8, rgba16f) uniform writeonly image2D out_albedo;
#endif

layout(push_constant) uniform GBufferResolve {
    uint table_base; // first entry of this frame slot's draw table
} resolve;

vec3 vertex_position(uint v) {
    return vec3(vertex_data[8u * v], vertex_data[8u * v + 1u], vertex_data[8u * v + 2u]);
}

vec3 vertex_normal(uint v) {
    return vec3(vertex_data[8u * v + 3u], vertex_data[8u * v + 4u], vertex_data[8u * v + 5u]);
}

vec3 place_with(vec4 x, vec4 y, vec4 z, vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec3(dot(x, h), dot(y, h), dot(z, h));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    uint id = imageLoad(visibility, pixel).r;
    if (id == 0u) {
        // Background: what the raster G-buffer's clear leaves.
        imageStore(out_position, pixel, vec4(0.0));
        imageStore(out_normal, pixel, vec4(0.0));
        imageStore(out_motion, pixel, vec4(0.0));
#ifndef TEXTURED_SCENE
        imageStore(out_albedo, pixel, vec4(0.0));
#endif
        return;
    }
    uint triangle = id - 1u;
    // Member by member: naga reads no whole-struct copies out of a buffer (OpCopyLogical).
    uint entry = resolve.table_base + triangle_draw[triangle];
    vec4 model_x = draws[entry].model_x, model_y = draws[entry].model_y;
    vec4 model_z = draws[entry].model_z;
    uint i0 = index_data[3u * triangle];
    uint i1 = index_data[3u * triangle + 1u];
    uint i2 = index_data[3u * triangle + 2u];
    vec3 p0 = place_with(model_x, model_y, model_z, vertex_position(i0));
    vec3 p1 = place_with(model_x, model_y, model_z, vertex_position(i1));
    vec3 p2 = place_with(model_x, model_y, model_z, vertex_position(i2));

    vec4 c0 = frame.view_proj * vec4(p0, 1.0);
    vec4 c1 = frame.view_proj * vec4(p1, 1.0);
    vec4 c2 = frame.view_proj * vec4(p2, 1.0);
    vec2 q = (vec2(pixel) + 0.5) / vec2(frame.size) * 2.0 - 1.0;
    vec3 b = cross(vec3(c0.x, c1.x, c2.x) - q.x * vec3(c0.w, c1.w, c2.w),
                   vec3(c0.y, c1.y, c2.y) - q.y * vec3(c0.w, c1.w, c2.w));
    float sum = b.x + b.y + b.z;
    // The rasterizer covered this pixel, so the sum is only 0 for a triangle seen edge-on
    // (zero area on screen): its centroid then stands for it. The comparison is false for
    // NaN, which takes the same path.
    b = abs(sum) > 0.0 ? b / sum : vec3(1.0 / 3.0);

    vec3 position = b.x * p0 + b.y * p1 + b.z * p2;
    vec4 prev_x = draws[entry].prev_model_x, prev_y = draws[entry].prev_model_y;
    vec4 prev_z = draws[entry].prev_model_z;
    // What stood still (both poses equal, as every static draw's identity rows) did not
    // move: the same products give the same point, so its motion is exactly 0 without them.
    vec3 prev = position;
    if (prev_x != model_x || prev_y != model_y || prev_z != model_z) {
        vec3 prev0 = place_with(prev_x, prev_y, prev_z, vertex_position(i0));
        vec3 prev1 = place_with(prev_x, prev_y, prev_z, vertex_position(i1));
        vec3 prev2 = place_with(prev_x, prev_y, prev_z, vertex_position(i2));
        prev = b.x * prev0 + b.y * prev1 + b.z * prev2;
    }
    vec3 n = b.x * vertex_normal(i0) + b.y * vertex_normal(i1) + b.z * vertex_normal(i2);
    n = vec3(dot(model_x.xyz, n), dot(model_y.xyz, n), dot(model_z.xyz, n));

    vec3 to_eye = frame.camera_pos - position;
    n = safe_normalize(n, safe_normalize(to_eye, vec3(0.0, 1.0, 0.0)));
    // The triangle's own plane decides the visible side, as the raster pass's screen
    // derivatives do (two_sided.glsl).
    n = visible_side_of(n, cross(p1 - p0, p2 - p0), position, frame.camera_pos);

    imageStore(out_position, pixel, vec4(position, 1.0));
    imageStore(out_normal, pixel, vec4(n, 0.0));
    imageStore(out_motion, pixel, vec4(position - prev, 0.0));
#ifndef TEXTURED_SCENE
    imageStore(out_albedo, pixel, vec4(draws[entry].albedo.rgb, 1.0));
#endif
}
