#version 460
// GTAO's own spatial denoise without the cache (XeGTAO filters its noisy output the same way,
// edge-aware, before any temporal step): a 5x5 window whose screen weights are 1 2 2 2 1 along
// each axis, times the tap's normal agreement (max(0, n . n_q)^16) and its distance from the
// centre's tangent plane in pixel footprints (a Gaussian of sigma 2), the joint bilateral
// filter's edge terms (shaders/jbf). The screen weights give each of the 16 slice rotations of
// a 4x4 tile (gtao.glsl's Bayer ranks) the same total weight, the two end taps of a row sharing
// one rotation, so on a plane the filter averages every slice direction; the thesis's 5x5
// Gaussian weighs them 1 to 36 and blurs across depth edges.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D ao_in;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D ao_out;

const float W[5] = float[5](1.0, 2.0, 2.0, 2.0, 1.0);
const float NORMAL_POWER = 16.0;
const float PLANE_SIGMA = 2.0; // pixel footprints

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 g = texelFetch(g_position, pixel, 0);
    if (g.w == 0.0) {
        imageStore(ao_out, pixel, texelFetch(ao_in, pixel, 0));
        return;
    }
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float footprint = 2.0 * distance(g.xyz, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y);
    // A footprint of 0 (a surface at the eye) would divide by 0: 1e-30 is below any scene's.
    float inv_plane = 1.0 / max(PLANE_SIGMA * footprint, 1e-30);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (outside_frame(q)) continue;
            vec4 gq = texelFetch(g_position, q, 0);
            if (gq.w == 0.0) continue;
            float plane = dot(n, gq.xyz - g.xyz) * inv_plane;
            float w = W[i + 2] * W[j + 2] * exp(-plane * plane) *
                      pow(max(dot(n, texelFetch(g_normal, q, 0).xyz), 0.0), NORMAL_POWER);
            sum += w * texelFetch(ao_in, q, 0);
            weights += w;
        }
    }
    // The centre weighs 4 (its normal and plane agree with themselves): weights >= 4.
    imageStore(ao_out, pixel, sum / max(weights, 1.0));
}
