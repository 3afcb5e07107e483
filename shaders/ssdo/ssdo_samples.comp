#version 460
// SSDO's pre-pass (Szentandrasi sections 4.2-4.3): at 1/scale resolution, how much the normals
// and the surfaces change around each block, and from that the number of hemisphere samples
// its pixels take: whole Halton periods (10, 20, ... from --ssdo-samples adaptive:MIN-MAX), one
// period more for each threshold the change exceeds. Low-resolution texel t looks at the 3x3
// block centres around it, `scale` pixels apart (wider areas around discontinuities, as the
// paper suggests), and takes the largest of
//  - 1 - n . n' over the neighbours' normals (creases: 0 on a plane, 1 at a right angle);
//  - |(p' - p) . n| / (scale footprints): a neighbour's distance from the centre's tangent
//    plane in units of the block's world size at the centre's depth (depth discontinuities;
//    0 on a plane at any slant, where a depth gradient would not be), at most 1.
// Background neighbours are skipped (nothing occludes from there).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "ssdo_params.glsl"
#include "halton.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2, r32ui) uniform writeonly uimage2D samples_out;

// The change measure of low-resolution texel t (also written by the tests' CPU check).
float block_change(ivec2 t, int scale) {
    ivec2 last = ivec2(frame.size) - 1;
    ivec2 c = min(t * scale + scale / 2, last);
    vec4 p = texelFetch(g_position, c, 0);
    if (p.w == 0.0) return 0.0;
    vec3 n = texelFetch(g_normal, c, 0).xyz;
    float depth = max((frame.view_proj * vec4(p.xyz, 1.0)).w, 1e-30);
    float block = float(scale) * 2.0 * frame.tan_half_fov * depth / float(frame.size.y);
    float change = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(c + ivec2(dx, dy) * scale, ivec2(0), last);
            vec4 qp = texelFetch(g_position, q, 0);
            if (qp.w == 0.0) continue;
            vec3 qn = texelFetch(g_normal, q, 0).xyz;
            float crease = 1.0 - clamp(dot(n, qn), -1.0, 1.0);
            float step = min(abs(dot(qp.xyz - p.xyz, n)) / block, 1.0);
            change = max(change, max(crease, step));
        }
    }
    return change;
}

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(samples_out)))) return;
    float change = block_change(t, int(ssdo.prepass_scale));
    uint periods = 0u;
    for (uint i = 0u; i < 4u; ++i)
        periods += uint(i < ssdo.threshold_count && change > ssdo.thresholds[i]);
    imageStore(samples_out, t, uvec4(ssdo.min_samples + HALTON_PERIOD * periods));
}
