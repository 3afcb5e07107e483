// Constants the shaders and the Rust side both use, defined here once: build.rs reads every
// `#define NAME VALUE` line of this file and generates `pub const NAME` in crate::shaders, so
// the two sides cannot drift. VALUE is an unsigned integer (`64u`: a u32) or a storage image
// format (`rgba32f`: an ash::vk::Format); anything else fails the build.
#ifndef SHARED_CONSTANTS_GLSL
#define SHARED_CONSTANTS_GLSL

// Lanes of a spread workgroup (indirect_spread.comp: one estimate's VPLs over up to this many
// lanes, several estimates per workgroup when they need fewer).
#define SPREAD_LANES 64u

// Threads sharing out one refresh-tile pixel's patterns (refresh.glsl); config.rs bounds the
// per-thread loop with it.
#define REFRESH_THREADS 64u

// Where a moving object changes a lane's value (reproject.comp; MovedReach::code in
// resources/temporal_effect.rs), tested against the box around every object that moved.
#define MOVED_SCREEN 1u // a screen-space estimate's taps can see it on the screen
#define MOVED_SHADOW 2u // in the box, or on its footprint on the shadow map
#define MOVED_INSIDE 3u // in the box (what the gather receives on moved)

// The AO estimators (ao.glsl; AoEstimator::code in effects/ao/config.rs).
#define AO_THESIS 0u
#define AO_CRYTEK 1u
#define AO_SZENTANDRASI 2u
#define AO_GTAO 3u

// How a fresh estimate merges into a history (frame.accumulate_mode; Accumulate::code in
// config/mod.rs): Lin 2013 eqs 4-5, an exponential moving average, a capped running mean, or
// the gated running mean (temporal.glsl's fresh_weight).
#define ACCUMULATE_CONFIDENCE 0u
#define ACCUMULATE_EMA 1u
#define ACCUMULATE_MEAN 2u
#define ACCUMULATE_GATED 3u

// How a moving camera reads a history between texels (frame.history_resample;
// HistoryResample::code): the best-registered tap, or the bilinear blend (reproject.comp).
#define HISTORY_RESAMPLE_POINT 0u
#define HISTORY_RESAMPLE_BILINEAR 1u

// How SVGF reads last frame's values (its push constant `bilinear`; SvgfHistory::code).
#define SVGF_HISTORY_NEAREST 0u
#define SVGF_HISTORY_BILINEAR 1u

// Storage image formats: the layout qualifier of every shader that binds the image as storage,
// and the format the Rust side makes it with (passes::decl checks the two agree at bind time).
// Each temporal effect's history (rgb value, a = estimates), named in its EffectKind. fp32 so
// that every update of a running mean counts: in fp16 a value in [0.5, 1) ignores changes
// below 2.4e-4, which the 36th pattern of a mean (1/37 of a difference of 0.01) already is.
#define AO_HISTORY_FORMAT rgba32f
#define SHADOW_HISTORY_FORMAT rgba32f
#define INDIRECT_HISTORY_FORMAT rgba32f
#define SSDO_HISTORY_FORMAT rgba32f
// Every temporal effect's moments (r: mean squared luminance of the estimates, g: the side of
// a pending gate crossing of the gated mean, b: estimates in that mean since its last restart;
// temporal.glsl). rgba32f rather than rg32f: a storage format every Vulkan device supports
// without shaderStorageImageExtendedFormats.
#define MOMENTS_FORMAT rgba32f
// A history's registration: rgb = the surface point each value belongs to (world units, fp32
// like the G-buffer position), a = area magnification since the counts were last scaled.
#define REGISTRATION_FORMAT rgba32f
// A temporal effect's per-pixel reprojection state (temporal.glsl's bits).
#define STATE_FORMAT r32ui

#endif // SHARED_CONSTANTS_GLSL
