// Per-effect GPU counters and work lists (indirect dispatch arguments first). build.rs
// generates the Rust struct `CountersHeader` from the header; the CPU resets it every frame.
#ifndef COUNTERS_GLSL
#define COUNTERS_GLSL

#ifndef COUNTERS_BINDING
#error "define COUNTERS_BINDING (the binding of the counters buffer in set 1) before including counters.glsl"
#endif
layout(set = 1, binding = COUNTERS_BINDING, std430) buffer Counters {
    uint dispatch_x;         // work blocks listed (indirect dispatch x), y = z = 1
    uint dispatch_y;
    uint dispatch_z;
    uint disoccluded_pixels; // pixels that failed eq 3 (or had no history)
    uint computed_pixels;    // pixels the effect evaluated (low-resolution ones for half res)
    uint fixup_pixels;       // full-resolution fix-ups (half-resolution indirect light)
    uint max_blocks;         // size of the block list; the fix-up list follows it in `data`
    uint fixup_dispatch_x;   // ceil(fixup_pixels / 64), y = z = 1
    uint fixup_dispatch_y;
    uint fixup_dispatch_z;
    uint data[];             // blocks (x | y << 16), then fix-up pixels (x | y << 16)
} counters;

#endif // COUNTERS_GLSL
