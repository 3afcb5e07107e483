// Per-effect GPU counters and work lists (indirect dispatch arguments first). build.rs
// generates the Rust struct `CountersHeader` from the block `Counters`; the CPU resets it
// every frame. The members, in order:
//   dispatch_x, _y, _z        the list's workgroups (one per block, or per 64 single pixels for
//                             block shift 0) as x * y, x at most frame.max_groups_x; z = 1
//   listed_pixels             entries of a list of single pixels
//   listed_blocks             entries of a list of work blocks
//   disoccluded_pixels        pixels that failed eq 3 (or had no history)
//   computed_pixels           pixels the effect evaluated (low-resolution ones for half res)
//   fixup_pixels              full-resolution fix-ups (half-resolution indirect light)
//   max_blocks                size of the block list; the fix-up list follows it in `data`
//   fixup_dispatch_x, _y, _z  ceil(fixup_pixels / 64), y = z = 1
//   refresh_evaluations       pattern evaluations of the refresh tile (every pattern counts)
//   samples                   samples taken, summed over computed_pixels (a per-pixel count)
//   invalidated_pixels        pixels whose history held but a moving object's reach dropped it
//   lowres_samples            low-resolution samples listed for the gather (half-res indirect)
//   lowres_dispatch_x, _y, _z the spread gather's workgroups (classify), y = z = 1
//   lowres_list               index in `data` of the low-resolution sample list
//   {gather,fixup,refresh}_   work efficiency of the effect's estimating passes, each:
//     invocations             lanes launched (workgroups x local size, per pass over a list)
//     active_invocations      lanes that evaluated an estimate (or part of one)
//     serial_evaluations      the most estimator evaluations (VPLs, taps, samples) one lane ran
//   data[]                    blocks (x | y << 16), then fix-up pixels, then low-resolution
//                             samples (x | y << 16)
// COUNTERS_MEMBERS lets a pass that fills several effects' lists (the reprojection) declare
// one block per effect with the same layout.
#ifndef COUNTERS_GLSL
#define COUNTERS_GLSL

#define COUNTERS_MEMBERS                                                                       \
    uint dispatch_x;                                                                           \
    uint dispatch_y;                                                                           \
    uint dispatch_z;                                                                           \
    uint listed_pixels;                                                                        \
    uint listed_blocks;                                                                        \
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
    uint lowres_samples;                                                                       \
    uint lowres_dispatch_x;                                                                    \
    uint lowres_dispatch_y;                                                                    \
    uint lowres_dispatch_z;                                                                    \
    uint lowres_list;                                                                          \
    uint gather_invocations;                                                                   \
    uint gather_active_invocations;                                                            \
    uint gather_serial_evaluations;                                                            \
    uint fixup_invocations;                                                                    \
    uint fixup_active_invocations;                                                             \
    uint fixup_serial_evaluations;                                                             \
    uint refresh_invocations;                                                                  \
    uint refresh_active_invocations;                                                           \
    uint refresh_serial_evaluations;                                                           \
    uint data[];

#ifndef COUNTERS_LANES
#ifndef COUNTERS_BINDING
#error "define COUNTERS_BINDING (the binding of the counters buffer in set 1) before including counters.glsl"
#endif
layout(set = 1, binding = COUNTERS_BINDING, std430) buffer Counters {
    COUNTERS_MEMBERS
} counters;
#endif

// This workgroup's index in a work list's x * y dispatch (the reprojection's LIST_DISPATCH:
// past the device's maxComputeWorkGroupCount[0] a list's groups continue in y). Groups past
// the list's end (x * y rounds up) have no entry.
uint listed_group() {
    return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
}

#ifndef COUNTERS_LANES
// One workgroup's share of a pass's work-efficiency counters, called by one invocation per
// workgroup: `launched` lanes, `active` of them evaluating, the most evaluations of one lane.
#define COUNT_WORK(role, launched, active, serial)                                              \
    {                                                                                          \
        atomicAdd(counters.role##_invocations, launched);                                      \
        if ((active) > 0u) atomicAdd(counters.role##_active_invocations, active);              \
        if ((serial) > 0u) atomicMax(counters.role##_serial_evaluations, serial);              \
    }
#endif

#endif // COUNTERS_GLSL
