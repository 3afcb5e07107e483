// GPU counters and the work list of 8x8 pixel blocks (indirect dispatch arguments first).
// Mirrors `Counters` in src/renderer/counters.rs.
layout(set = 1, binding = COUNTERS_BINDING, std430) buffer Counters {
    uint dispatch_x;          // blocks that need work (indirect dispatch x)
    uint dispatch_y;          // 1
    uint dispatch_z;          // 1
    uint disoccluded_pixels;  // pixels that failed eq 3 (or had no history)
    uint ssao_computed_pixels;// pixels the SSAO pass evaluated
    uint reserved0;
    uint reserved1;
    uint reserved2;
    uint blocks[];            // packed block coordinates: x | y << 16
} counters;
