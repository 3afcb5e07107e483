// Per-frame constants shared by every pass (set 0, binding 0). Mirrors `FrameUniforms` in
// src/renderer/frame.rs; std140, every member 16-byte aligned.
layout(set = 0, binding = 0, std140) uniform Frame {
    mat4 view_proj;        // camera, world -> clip (Vulkan: y down, depth 0..1)
    mat4 prev_view_proj;   // last frame's camera (eq 1)
    mat4 light_view_proj;  // spot light, world -> clip
    vec4 camera_pos;       // xyz, w = tan(vertical fov / 2)
    vec4 light_pos;        // xyz, w = cos(outer half-angle)
    vec4 light_dir;        // xyz unit axis, w = cos(inner half-angle)
    vec4 light_intensity;  // rgb radiant intensity on the axis [W/sr], w = light near plane
    vec4 light_params;     // x = light far plane, y = tan(half fov of the shadow frustum),
                           // z = shadow map size [texels], w = PCF kernel radius [texels]
    vec4 ambient;          // rgb ambient radiance
    uvec4 size;            // width, height, frame index, PCF grid side or disc samples
    uvec4 temporal;        // x = history valid (camera), yz unused,
                           // w = rotation limit (patterns until converged)
    vec4 temporal_params;  // x = accumulation (0 confidence, 1 EMA, 2 mean), y = its parameter
                           // (bias / alpha / cap), z = epsilon, w = 0 relative, 1 absolute
    vec4 ao_params;        // x = world radius, y = a, z = b (eq 7), w = nearest step [px]
    uvec4 ao_config;       // x = directions, y = steps (thesis) or samples (crytek),
                           // z = patterns per evaluation, w = 0 thesis, 1 crytek
    vec4 ao_pattern;       // x = rotation per pattern [rad], y = pattern offset,
                           // z = PCF kernel (0 grid, 1 disc)
    vec4 indirect_params;  // x = VPLs per gather (0 = every RSM texel), y = screen-space
                           // visibility test (0/1), z = half resolution (0/1)
} frame;

const float PI = 3.14159265358979;

// Normalise with a fallback: |v|^2 below 1e-20 means a degenerate direction (interpolated
// normals and light vectors are O(1) or scene-scale, never legitimately that small).
vec3 safe_normalize(vec3 v, vec3 fallback) {
    float len2 = dot(v, v);
    return len2 > 1e-20 ? v * inversesqrt(len2) : fallback;
}

// Smooth spot cone: 1 inside the inner angle, 0 outside the outer, Hermite in between.
float spot_factor(vec3 to_point_unit) {
    float c = dot(frame.light_dir.xyz, to_point_unit);
    return smoothstep(frame.light_pos.w, frame.light_dir.w, c);
}

// View-space distance along the light axis from a stored shadow-map depth (perspective,
// depth 0 at near, 1 at far).
float light_linear_depth(float ndc_depth) {
    float n = frame.light_intensity.w;
    float f = frame.light_params.x;
    return n * f / max(f - ndc_depth * (f - n), 1e-30);
}
