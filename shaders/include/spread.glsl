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

// Lanes that share one estimate are the VPL parameters' gather_lanes and spread_lanes, computed
// once on the CPU (effects/indirect/params.rs lanes_per_estimate); a workgroup takes
// SPREAD_LANES / lanes estimates at once.

#endif // SPREAD_GLSL
