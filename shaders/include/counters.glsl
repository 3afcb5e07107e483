// Per-effect GPU counters and work lists (indirect dispatch arguments first). build.rs
// generates the Rust struct `CountersHeader` from the block `Counters`; the CPU resets it
// every frame. The members, in order:
//   dispatch_x, _y, _z        work blocks listed (indirect dispatch x), y = z = 1
//   disoccluded_pixels        pixels that failed eq 3 (or had no history)
//   computed_pixels           pixels the effect evaluated (low-resolution ones for half res)
//   fixup_pixels              full-resolution fix-ups (half-resolution indirect light)
//   max_blocks                size of the block list; the fix-up list follows it in `data`
//   fixup_dispatch_x, _y, _z  ceil(fixup_pixels / 64), y = z = 1
//   refresh_evaluations       pattern evaluations of the refresh tile (every pattern counts)
//   samples                   hemisphere samples taken (SSDO: their sum over computed_pixels)
//   invalidated_pixels        pixels whose history held but a moving object's reach dropped it
//   data[]                    blocks (x | y << 16), then fix-up pixels (x | y << 16)
// COUNTERS_MEMBERS lets a pass that fills several effects' lists (the reprojection) declare
// one block per effect with the same layout.
#ifndef COUNTERS_GLSL
#define COUNTERS_GLSL

#define COUNTERS_MEMBERS                                                                       \
    uint dispatch_x;                                                                           \
    uint dispatch_y;                                                                           \
    uint dispatch_z;                                                                           \
    uint disoccluded_pixels;                                                                   \
    uint computed_pixels;                                                                      \
    uint fixup_pixels;                                                                         \
    uint max_blocks;                                                                           \
    uint fixup_dispatch_x;                                                                     \
    uint fixup_dispatch_y;                                                                     \
    uint fixup_dispatch_z;                                                                     \
    uint refresh_evaluations;                                                                  \
    uint samples;                                                                              \
    uint invalidated_pixels;                                                                   \
    uint data[];

#ifndef COUNTERS_LANES
#ifndef COUNTERS_BINDING
#error "define COUNTERS_BINDING (the binding of the counters buffer in set 1) before including counters.glsl"
#endif
layout(set = 1, binding = COUNTERS_BINDING, std430) buffer Counters {
    COUNTERS_MEMBERS
} counters;
#endif

#endif // COUNTERS_GLSL
