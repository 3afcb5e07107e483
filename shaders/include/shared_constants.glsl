// Constants the shaders and the Rust side both use, defined here once: build.rs reads every
// `#define NAME VALUEu` line of this file and generates `pub const NAME: u32 = VALUE;` in
// crate::shaders, so the two sides cannot drift. Plain unsigned integers only.
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

#endif // SHARED_CONSTANTS_GLSL
