// Push constants shared by the reprojection and the effect passes of one temporal effect.
layout(push_constant) uniform Effect {
    uvec4 refresh;    // xy = refresh tile origin [px] (~0 = none), z = tile side, w = history valid
    uvec4 block;      // x = log2 of the work-block side (3: 8x8, 4: 16x16), y = frame pattern
} effect;

// Full-resolution pixel of local invocation `local` in listed work block `index`.
ivec2 block_pixel(uint index, uvec2 local) {
    uint packed = counters.data[index];
    return ivec2(uvec2(packed & 0xffffu, packed >> 16) << effect.block.x) + ivec2(local);
}
