#version 460
// Point-sampled levels of the G-buffer position for SSAO's far taps (--ao-position-mips).
// Level L texel t holds the position of pixel t * 2^L + 2^(L-1), the pixel at the texel's
// centre: a real surface point (averaging the 2^L x 2^L pixels would invent surfaces across
// depth edges), at most 2^(L-1) pixels from any tap that reads it. One thread per level-1 texel
// writes it, and the level-2 and level-3 texels whose corner it is, so the levels need no
// barrier between them.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1, rgba32f) uniform writeonly image2D level1;
layout(set = 1, binding = 2, rgba32f) uniform writeonly image2D level2;
layout(set = 1, binding = 3, rgba32f) uniform writeonly image2D level3;

vec4 centre_position(ivec2 texel, int level) {
    ivec2 pixel = texel * (1 << level) + (1 << (level - 1));
    return texelFetch(g_position, min(pixel, ivec2(frame.size) - 1), 0);
}

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(t, imageSize(level1)))) return;
    imageStore(level1, t, centre_position(t, 1));
    // Level sizes are ceil(size / 2^L), so every level-2 and level-3 texel has its corner
    // thread in the level-1 grid.
    if (all(equal(t & 1, ivec2(0)))) imageStore(level2, t >> 1, centre_position(t >> 1, 2));
    if (all(equal(t & 3, ivec2(0)))) imageStore(level3, t >> 2, centre_position(t >> 2, 3));
}
