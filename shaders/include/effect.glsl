// Push constants shared by the reprojection and the effect passes of one temporal effect.
// build.rs generates the Rust struct `EffectPush` from this declaration.
#ifndef EFFECT_GLSL
#define EFFECT_GLSL

#include "counters.glsl"
#include "frame.glsl"

layout(push_constant) uniform Effect {
    uvec4 refresh_rect;    // refresh tile [x0, x1) x [y0, y1) as (x0, y0, x1, y1) [px]; empty = none
    uint refresh_feather;  // width of the refresh tile's blend ramp [px]; 0 = hard tile
    uint history_valid;    // 0 on the first frame, after a resize or a camera cut
    uint block_shift;      // log2 of the work-block side (3: 8x8, 4: 16x16; 0: single pixels)
    uint pattern;          // this frame's pattern index
} effect;

// Full-resolution pixel of local invocation `local` of this workgroup (listed_group() w) in
// a list of work blocks (block w's pixel), or of single pixels (block shift 0: entry 64 w + i
// for invocation i); (-1, -1), outside the frame, past the list's end.
ivec2 block_pixel(uvec2 local) {
    uint group = listed_group();
    if (effect.block_shift == 0u) {
        uint i = group * 64u + local.y * 8u + local.x;
        if (i >= counters.listed_pixels) return ivec2(-1);
        uint packed = counters.data[i];
        return ivec2(packed & 0xffffu, packed >> 16);
    }
    if (group >= counters.listed_blocks) return ivec2(-1);
    uint packed = counters.data[group];
    return ivec2(uvec2(packed & 0xffffu, packed >> 16) << effect.block_shift) + ivec2(local);
}

// Pixels of this frame's refresh tile (0: none), and pixel i of it, in rows.
uint refresh_tile_pixels() {
    uvec4 r = effect.refresh_rect;
    return r.z > r.x && r.w > r.y ? (r.z - r.x) * (r.w - r.y) : 0u;
}

ivec2 refresh_tile_pixel(uint i) {
    uvec4 r = effect.refresh_rect;
    uint width = max(r.z - r.x, 1u);
    return ivec2(r.x + i % width, r.y + i / width);
}

// Whether full-resolution pixel `pixel` lies in this frame's refresh tile.
bool in_refresh_tile(ivec2 pixel) {
    uvec4 r = effect.refresh_rect;
    return all(greaterThanEqual(uvec2(pixel), r.xy)) && all(lessThan(uvec2(pixel), r.zw));
}

// Weight of the recomputed value in a refreshed pixel: 1 in the tile's core, falling linearly
// to 1 / (2 feather) at the pixels next to a tile edge, so a tile whose neighbours have drifted
// (a screen-space effect seen from elsewhere, histories smoothed by resampling) meets them in
// a ramp instead of a step (the seams of the thesis's Figure 4.4). Edges on the image border
// have no neighbour and are not feathered. The schedule (temporal.rs) shifts the tile grid by
// half a tile from cycle to cycle, so every pixel lies in some tile's core.
float refresh_weight(ivec2 pixel) {
    if (effect.refresh_feather == 0u) return 1.0;
    uvec4 r = effect.refresh_rect;
    float feather = float(effect.refresh_feather);
    vec2 c = vec2(pixel) + 0.5;
    vec2 lo = mix(c - vec2(r.xy), vec2(feather), equal(r.xy, uvec2(0u)));
    vec2 hi = mix(vec2(r.zw) - c, vec2(feather), greaterThanEqual(r.zw, frame.size));
    vec2 d = min(lo, hi);
    return clamp(min(d.x, d.y) / feather, 0.0, 1.0);
}

#endif // EFFECT_GLSL
