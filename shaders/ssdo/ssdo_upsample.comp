#version 460
// Joint bilateral upsampling (Kopf et al. 2007) of half-resolution SSDO (Szentandrasi section
// 4.1): each full-resolution pixel averages the 3x3 low-resolution texels around it, texel t
// standing for the G-buffer's pixel t * scale, with the weights of the bilateral filter
// (shaders/ssdo/ssdo_bilateral.comp) guided by the full-resolution G-buffer:
//  - a Gaussian of the distance from the pixel to the texel's pixel (sigma = scale pixels);
//  - exp(-(h / 2 footprints)^2), h the texel's distance from the pixel's tangent plane;
//  - exp(-((1 - n . n') / 0.1)^2) of the normals.
// A pixel whose texels all lie on other surfaces (a one-pixel sliver the low-resolution grid
// missed) takes the texel nearest its tangent plane rather than a blend across the edge.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "ssdo_params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D src;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D dst;

// Below this total weight the geometry weights rejected every texel: exp(-9) is a texel six
// footprints off the tangent plane or normals ~45 degrees apart; footprints keep it scale-free.
const float MIN_WEIGHT = 1.2e-4;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (outside_frame(pixel)) return;
    vec4 position = texelFetch(g_position, pixel, 0);
    if (position.w == 0.0) {
        imageStore(dst, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    int scale = int(ssdo.scale);
    ivec2 low_size = textureSize(src, 0);
    vec3 p = position.xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float depth = max((frame.view_proj * vec4(p, 1.0)).w, 1e-30);
    float footprint = 2.0 * frame.tan_half_fov * depth / float(frame.size.y);
    float inv_plane = 1.0 / (2.0 * footprint);
    float inv_two_sigma2 = 1.0 / (2.0 * float(scale * scale));
    ivec2 base = pixel / scale;
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    vec4 nearest = vec4(0.0, 0.0, 0.0, 1.0);
    float nearest_h = 1e30;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = base + ivec2(dx, dy);
            if (any(greaterThanEqual(uvec2(t), uvec2(low_size)))) continue;
            ivec2 q = t * scale;
            vec4 qp = texelFetch(g_position, q, 0);
            if (qp.w == 0.0) continue;
            vec3 qn = texelFetch(g_normal, q, 0).xyz;
            vec4 value = texelFetch(src, t, 0);
            float h = dot(qp.xyz - p, n) * inv_plane;
            float c = (1.0 - clamp(dot(n, qn), 0.0, 1.0)) * 10.0;
            vec2 d = vec2(q - pixel);
            float w = exp(-dot(d, d) * inv_two_sigma2 - h * h - c * c);
            sum += w * value;
            weights += w;
            if (abs(h) + c < nearest_h) {
                nearest_h = abs(h) + c;
                nearest = value;
            }
        }
    }
    imageStore(dst, pixel, weights > MIN_WEIGHT ? sum / weights : nearest);
}
