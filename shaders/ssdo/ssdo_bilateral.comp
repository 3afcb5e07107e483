#version 460
// Separable geometry-aware bilateral filter (Szentandrasi section 4.1 after Reinbothe et al.):
// a horizontal then a vertical pass of side 2 r + 1 (11 by default) over SSDO's rgba (bounce,
// modulation factor), each channel filtered on its own with the same weights. A neighbour's
// weight is a Gaussian of its pixel distance (sigma = side / 4) times
//  - exp(-(h / 2 footprints)^2), h its distance from the centre pixel's tangent plane and a
//    footprint the pixel's world size at the centre's depth: 0 on the same plane at any slant
//    and any scale, so planes are smoothed fully and a depth edge not at all;
//  - exp(-((1 - n . n') / 0.1)^2): 0.98 at 10 degrees between the normals, 1e-44 at 90.
// At SSDO's 1/scale resolution, texel t stands for the G-buffer's pixel t * scale and a
// footprint is scale pixels wide.
// @permutation horizontal: HORIZONTAL
// @permutation vertical: VERTICAL
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "ssdo_params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D src;
layout(set = 1, binding = 3, rgba16f) uniform writeonly image2D dst;

#ifdef HORIZONTAL
const ivec2 AXIS = ivec2(1, 0);
#else
const ivec2 AXIS = ivec2(0, 1);
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 grid = imageSize(dst);
    if (any(greaterThanEqual(pixel, grid))) return;
    int scale = int(ssdo.scale);
    vec4 centre = texelFetch(src, pixel, 0);
    vec4 position = texelFetch(g_position, pixel * scale, 0);
    int radius = int(ssdo.filter_radius);
    if (position.w == 0.0 || radius == 0) {
        imageStore(dst, pixel, centre);
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(g_normal, pixel * scale, 0).xyz;
    float depth = max((frame.view_proj * vec4(p, 1.0)).w, 1e-30);
    float footprint = float(scale) * 2.0 * frame.tan_half_fov * depth / float(frame.size.y);
    float inv_plane = 1.0 / (2.0 * footprint);
    float sigma = float(2 * radius + 1) / 4.0;
    float inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
    vec4 sum = centre;
    float weights = 1.0;
    for (int k = -radius; k <= radius; ++k) {
        if (k == 0) continue;
        ivec2 q = pixel + k * AXIS;
        if (any(greaterThanEqual(uvec2(q), uvec2(grid)))) continue;
        vec4 qp = texelFetch(g_position, q * scale, 0);
        if (qp.w == 0.0) continue;
        vec3 qn = texelFetch(g_normal, q * scale, 0).xyz;
        float h = dot(qp.xyz - p, n) * inv_plane;
        float c = (1.0 - clamp(dot(n, qn), 0.0, 1.0)) * 10.0;
        float w = exp(-float(k * k) * inv_two_sigma2 - h * h - c * c);
        sum += w * texelFetch(src, q, 0);
        weights += w;
    }
    imageStore(dst, pixel, sum / weights);
}
