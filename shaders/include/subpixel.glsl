// The subpixel geometry's samples: the 4x rotated grid (one sample in each row and each column of a
// 4x4 grid over the pixel), as offsets from the pixel centre [px]. The subpixel geometry
// renders shift the projection by these; the reconstruction reads them back.
#ifndef SUBPIXEL_GLSL
#define SUBPIXEL_GLSL

const vec2 SUBPIXEL_OFFSETS[4] = vec2[4](
    vec2(-0.125, -0.375),
    vec2(0.375, -0.125),
    vec2(-0.375, 0.125),
    vec2(0.125, 0.375)
);

#endif
