// Per-frame constants shared by every pass (set 0, binding 0), std430. build.rs generates the
// Rust struct `FrameBlock` from this declaration (src/renderer/frame.rs fills it by name), so
// the two sides cannot drift. One parameter per member.
//
// A read-only storage buffer, not a uniform buffer: lavapipe (Mesa 22.3, the CI device)
// inlines uniform-buffer values that feed loop and branch conditions into the shader and
// recompiles it whenever the buffer is bound again, i.e. every pass of every frame, without
// freeing the old code: 0.6 MB per frame for SSAO, 2.5 MB with indirect light, and frames
// slowed by the recompiles (`ssgi stress`'s long run found it). Storage-buffer loads are never
// inlined. On a GPU this trades the constant-buffer path for the read-only buffer path for a
// few reads per invocation.
#ifndef FRAME_GLSL
#define FRAME_GLSL

#include "common.glsl"

layout(set = 0, binding = 0, std430) readonly buffer Frame {
    mat4 view_proj;            // camera, world -> clip (Vulkan: y down, depth 0..1)
    mat4 prev_view_proj;       // last frame's camera (eq 1)
    mat4 light_view_proj;      // spot light, world -> clip
    vec3 camera_pos;
    float tan_half_fov;        // tan(camera's vertical fov / 2)
    vec3 light_pos;
    float light_cos_outer;     // cos(outer half-angle of the spot cone)
    vec3 light_dir;            // unit axis of the spot
    float light_cos_inner;     // cos(inner half-angle)
    vec3 light_intensity;      // rgb radiant intensity on the axis [W/sr]
    float light_near;          // light view's near plane
    vec3 ambient;              // rgb ambient radiance
    float light_far;           // light view's far plane
    uvec2 size;                // render width, height [px]
    uint frame_index;
    uint rotation_limit;       // patterns per pixel until it counts as converged
    float scene_radius;        // the scene's bounding radius: effects' radii are relative to it
    float light_tan_half_fov;  // tan(half fov of the shadow frustum)
    float shadow_map_size;     // side of the shadow map / RSM [texels]
    float pcf_radius;          // PCF kernel radius [texels]
    uint pcf_kernel;           // 0 grid, 1 rotated disc
    uint pcf_count;            // grid side, or disc samples
    uint accumulate_mode;      // ACCUMULATE_* (shared_constants.glsl)
    float accumulate_param;    // confidence bias / EMA alpha / mean cap / gate [sigmas]
    float epsilon;             // eq 3 threshold: texel footprints (relative) or world units
    uint epsilon_absolute;     // 0 relative, 1 absolute
    uint camera_static;        // 1 when prev_view_proj equals view_proj exactly (CPU test)
    uint indirect_input;       // test input: 0 the gather, 1 world position (IndirectInput::Ramp), 2 + i NaN at pixel index i (Renderer::plant_nan)
    vec3 prev_camera_pos;      // last frame's eye: the history's footprint on each surface
    uint history_resample;     // moving camera: HISTORY_RESAMPLE_* (shared_constants.glsl)
    vec4 moved_light_rect;     // the moved box's footprint on the shadow map (x0, y0, x1, y1) [texels]
    vec4 moved_screen_rect;    // its footprint on the screen (x0, y0, x1, y1) [px]
    vec3 moved_min;            // box around what moved since last frame, at both places (world)
    uint moved_count;          // objects that moved (0: nothing did; the box means nothing)
    vec3 moved_max;
    uint max_groups_x;         // a work list's dispatch in x: maxComputeWorkGroupCount[0] (test hook: less)
} frame;

// Smooth spot cone: 1 inside the inner angle, 0 outside the outer, Hermite in between. As on
// the CPU (SpotLight::spot_factor), an inner angle at or past the outer one makes the edge a
// hard step at the outer angle: smoothstep is undefined for edge0 >= edge1.
float spot_factor(vec3 to_point_unit) {
    float c = dot(frame.light_dir, to_point_unit);
    if (!(c >= frame.light_cos_outer)) return 0.0; // also NaN
    if (frame.light_cos_inner <= frame.light_cos_outer) return 1.0;
    return smoothstep(frame.light_cos_outer, frame.light_cos_inner, c);
}

// View-space distance along the light axis from a stored shadow-map depth (perspective,
// depth 0 at near, 1 at far).
float light_linear_depth(float ndc_depth) {
    float n = frame.light_near;
    float f = frame.light_far;
    return n * f / max(f - ndc_depth * (f - n), 1e-30);
}

// Whether `pixel` lies outside the render target (negative coordinates wrap to huge unsigned
// values, so one comparison covers both sides).
bool outside_frame(ivec2 pixel) {
    return any(greaterThanEqual(uvec2(pixel), frame.size));
}

// Test hook (Renderer::plant_nan): whether the indirect estimates of `pixel` are NaN this
// frame, to show the guards keep a NaN from spreading.
bool planted_nan(ivec2 pixel) {
    return frame.indirect_input >= 2u && !outside_frame(pixel) &&
           uint(pixel.y) * frame.size.x + uint(pixel.x) == frame.indirect_input - 2u;
}

// A quiet NaN: exponent all ones, quiet bit set. Built from a uniform so it is no constant
// (naga's validation refuses NaN constants); any mantissa bits below keep it a NaN.
float quiet_nan() {
    return uintBitsToFloat(0x7fc00000u | (frame.indirect_input & 0x3fffffu));
}

#endif // FRAME_GLSL
