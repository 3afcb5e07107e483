// One every-VPL estimate shared among lanes of a workgroup (indirect_spread.comp), and what
// the passes that size its dispatches need to know of it.
#ifndef SPREAD_GLSL
#define SPREAD_GLSL

#include "frame.glsl"
#include "shared_constants.glsl"
#include "vpl_params.glsl"

// Evaluations of eq 9 in one pattern's every-VPL gather (interleave 1).
uint rsm_gather_evaluations() {
    uint size = uint(frame.shadow_map_size);
    return vpl_params.count == 0u ? size * size : vpl_params.count;
}

// Lanes that share one estimate: `most` (a power of two up to SPREAD_LANES), or for fewer
// evaluations than that the next power of two, so that no lane idles for lack of VPLs; a
// workgroup takes SPREAD_LANES / lanes estimates at once. Also effects/indirect.rs's
// `lanes_per_estimate`.
uint spread_lanes_per_estimate(uint most) {
    uint work = rsm_gather_evaluations();
    uint lanes = 1u;
    while (lanes < work && lanes < most) lanes <<= 1u;
    return lanes;
}

#endif // SPREAD_GLSL
