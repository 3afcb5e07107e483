// SSAO's parameters: constant for a configuration, written once when the effect is made
// (src/effects/ao/params.rs). build.rs generates the Rust struct `AoParams` from this block.
// The estimating passes bind it at binding 15 of their set.
#ifndef AO_PARAMS_GLSL
#define AO_PARAMS_GLSL

layout(set = 1, binding = 15, std430) readonly buffer Ao {
    float radius;        // sampling radius, relative to frame.scene_radius
    float atten_a;       // eq 7: D(d) = 1 + a d + b d^2, d in units of the radius
    float atten_b;
    float near_px;       // nearest step [px] (eq 8)
    uint directions;     // thesis estimator: directions; GTAO: slices
    uint steps;          // thesis estimator: steps per direction; GTAO: steps per side
    uint samples;        // crytek and szentandrasi estimators: samples
    uint patterns;       // patterns per evaluation (1, or many for references)
    uint position_mips;  // far taps read point-sampled position levels up to this (0 = off)
    uint pattern_base;   // first pattern without reuse (0, or an independent range for references)
} ao;

#endif // AO_PARAMS_GLSL
