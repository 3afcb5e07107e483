// The VPL gather's parameters (IndirectConfig), shared by the gathers that read the RSM: the
// indirect light's cache and the noisy per-frame gather its filters take. Constant for a
// configuration: each effect that gathers writes its copy once (src/effects/indirect/
// params.rs) and binds it at 15. build.rs generates `VplParams`.
#ifndef VPL_PARAMS_GLSL
#define VPL_PARAMS_GLSL

layout(set = 1, binding = 15, std430) readonly buffer Vpl {
    uint count;          // VPLs per gather (0 = every RSM texel)
    uint visibility;     // screen-space visibility test of each VPL (0/1)
    float march_near_px; // nearest step of that visibility march [px]
    uint interleave;     // interleaved gather: block side N, one VPL subset per pixel (1 = off)
    uint gather_lanes;   // lanes sharing one estimate's VPLs in the compacted gather
                         // (--vpl-lanes, fewer for fewer VPLs: params.rs lanes_per_estimate)
    uint spread_lanes;   // the same for the few-pixel passes (up to SPREAD_LANES)
    uint noisy_half_res; // the noisy gather: one pixel per 2x2 block gathers (0/1)
} vpl_params;

#endif // VPL_PARAMS_GLSL
