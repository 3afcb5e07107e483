// SSDO's parameters: constant for a configuration, written once when the effect is made
// (src/effects/ssdo/params.rs). build.rs generates the Rust struct `SsdoParams` from this
// block. Every SSDO pass binds it at binding 15 of its set.
#ifndef SSDO_PARAMS_GLSL
#define SSDO_PARAMS_GLSL

layout(set = 1, binding = 15, std430) readonly buffer Ssdo {
    vec4 thresholds;      // change measure above which a block takes one Halton period more
    uint samples;         // hemisphere samples per pixel (K), without the pre-pass
    uint min_samples;     // with the pre-pass: a flat block's samples (whole Halton periods)
    uint prepass_scale;   // with the pre-pass: its resolution divisor
    uint threshold_count; // thresholds in use: 0 = fixed count, no pre-pass
    float radius;         // hemisphere radius r_max, relative to frame.scene_radius
    uint filter_radius;   // half side of the separable bilateral filter (0 = off)
    uint scale;           // resolution divisor: texel t samples pixel t * scale
    uint direct_enabled;  // 1 when the direct effect runs (the senders add its light)
} ssdo;

#endif // SSDO_PARAMS_GLSL
