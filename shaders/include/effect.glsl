// Push constants shared by the reprojection and the effect passes of one temporal effect.
// build.rs generates the Rust struct `EffectPush` from this declaration.
#ifndef EFFECT_GLSL
#define EFFECT_GLSL

#include "counters.glsl"

layout(push_constant) uniform Effect {
    uvec2 refresh_origin;  // refresh tile origin [px]; ~0 = no refresh this frame
    uint refresh_tile;     // refresh tile side [px]
    uint history_valid;    // 0 on the first frame, after a resize or a camera cut
    uint block_shift;      // log2 of the work-block side (3: 8x8, 4: 16x16)
    uint pattern;          // this frame's pattern index
} effect;

// Full-resolution pixel of local invocation `local` in listed work block `index`.
ivec2 block_pixel(uint index, uvec2 local) {
    uint packed = counters.data[index];
    return ivec2(uvec2(packed & 0xffffu, packed >> 16) << effect.block_shift) + ivec2(local);
}

// Whether full-resolution pixel `pixel` lies in this frame's refresh tile.
bool in_refresh_tile(ivec2 pixel) {
    uvec2 tile = effect.refresh_origin;
    return tile.x != 0xffffffffu && all(greaterThanEqual(uvec2(pixel), tile)) &&
           all(lessThan(uvec2(pixel), tile + effect.refresh_tile));
}

#endif // EFFECT_GLSL
