#version 460
// Reverse reprojection (Lin 2013 eqs 1-3) for every temporal effect at once. Per pixel, the
// G-buffer, the previous texture coordinate (eq 1) and the disocclusion test against the
// world-position and normal histories (eqs 2-3, FACING_ACCEPT) are read and computed once;
// then each effect (a "lane": its history, moments, state, counters and push constants)
// resamples its own history with that result, gets its per-pixel state, and lists its work
// blocks (the effect pass's indirect dispatch).
//
// LANES (1-3) is the number of temporal effects the renderer was built with, in registry
// order; a lane whose effect does not reproject this frame has `active` 0 and is left alone.
// Lane k's history has its effect's format, LANE_HISTORY_FORMAT_k: one permutation per
// combination of the history formats in use (build.rs's {HISTORY_FORMATS}).
// @permutation 1: LANES=1 LANE_HISTORY_FORMAT_0={HISTORY_FORMATS}
// @permutation 2: LANES=2 LANE_HISTORY_FORMAT_0={HISTORY_FORMATS} LANE_HISTORY_FORMAT_1={HISTORY_FORMATS}
// @permutation 3: LANES=3 LANE_HISTORY_FORMAT_0={HISTORY_FORMATS} LANE_HISTORY_FORMAT_1={HISTORY_FORMATS} LANE_HISTORY_FORMAT_2={HISTORY_FORMATS}
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#include "shared_constants.glsl"
#define COUNTERS_LANES
#include "counters.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D prev_position; // last frame's G-buffer position
layout(set = 1, binding = 3) uniform texture2D prev_normal;   // last frame's G-buffer normal
layout(set = 1, binding = 4) uniform texture2D g_motion;      // world-space motion since last frame

// Lane k's resources at bindings 8 + 8k ...: last frame's history (rgb value, a = estimates),
// this frame's, the state, the counters, last frame's moments and this frame's, last frame's
// registration and this frame's (lane_state).
#define LANE_RESOURCES(k)                                                                      \
    layout(set = 1, binding = 8 * k + 8) uniform texture2D history_prev_##k;                   \
    layout(set = 1, binding = 8 * k + 9, LANE_HISTORY_FORMAT_##k) uniform writeonly image2D history_cur_##k; \
    layout(set = 1, binding = 8 * k + 10, STATE_FORMAT) uniform writeonly uimage2D state_out_##k; \
    layout(set = 1, binding = 8 * k + 11, std430) buffer Counters##k {                         \
        COUNTERS_MEMBERS                                                                       \
    } counters_##k;                                                                            \
    layout(set = 1, binding = 8 * k + 12) uniform texture2D moments_prev_##k;                  \
    layout(set = 1, binding = 8 * k + 13, MOMENTS_FORMAT) uniform writeonly image2D moments_cur_##k; \
    layout(set = 1, binding = 8 * k + 14) uniform texture2D registration_prev_##k;             \
    layout(set = 1, binding = 8 * k + 15, REGISTRATION_FORMAT) uniform writeonly image2D registration_cur_##k;

LANE_RESOURCES(0)
#if LANES > 1
LANE_RESOURCES(1)
#endif
#if LANES > 2
LANE_RESOURCES(2)
#endif

// build.rs generates the Rust struct `ReprojectPush` from this block.
layout(push_constant) uniform Reproject {
    uvec4 refresh_rect_0; // lane k's refresh tile (x0, y0, x1, y1) [px]; empty = none
    uvec4 refresh_rect_1;
    uvec4 refresh_rect_2;
    uvec4 lane_0;         // lane k: (active, history_valid, log2 of the work-block side (0: a
                          //          list of single pixels), moving objects' reach: MOVED_*
                          //          (shared_constants.glsl) in bits 0-7, 0 = none;
                          //          MOVED_SCREEN's extra pixels above)
    uvec4 lane_1;
    uvec4 lane_2;
    uvec4 reaccumulate;   // x: bit k set = lane k starts re-accumulating this frame; y: bit k
                          //    set = a change (the light, a moving object) reached lane k's
                          //    values this frame: its re-accumulation ends
    vec4 reach_radius;    // lane k's sampling radius for MOVED_SCREEN, relative to the scene's
                          // bounding radius (frame.scene_radius)
} lanes;

// Beyond eq 3: a history texel must also face the pixel's way, within 60 degrees. The back of
// a thin wall (or of any two-sided sheet) has the front's position, and a camera passing
// through it would otherwise hand the unlit back's history to the lit front; a crease's other
// face (90 degrees) is another surface too. Curved surfaces turn far less between neighbouring
// texels at any useful resolution.
const float FACING_ACCEPT = 0.5;

// What every lane shares: where the pixel was last frame and which texels there hold it.
struct Reprojected {
    bool geometry; // the pixel shows a surface
    bool found;    // the nearest previous texel holds this surface (eqs 2-3 + facing)
    bool bilinear; // all four texels around the previous position do
    ivec2 nearest;
    ivec2 base;    // lower-left of the four
    vec2 w;        // bilinear weights
    float stretch; // area of the surface under last frame's pixel over this frame's (> 1: magnified)
    vec3 p;        // the pixel's surface point
    vec3 motion;   // how far that point moved in the world since last frame (a moving object)
};

// Pixel footprint on the surface at p (normal n) seen from `eye`, up to the lens factor (the
// same each frame): distance over |cos| of the view angle, the cosine floored at 0.1 as in eq
// 3's threshold.
float surface_footprint(vec3 p, vec3 n, vec3 eye) {
    vec3 to_eye = eye - p;
    float dist = length(to_eye);
    return dist / max(abs(dot(n, to_eye)) / max(dist, 1e-30), 0.1);
}

// A history's value is trusted only where it still belongs: each lane carries, per pixel, its
// registration (xyz: the surface point the value was estimated for, resampled with the value;
// w: the history's area magnification since its counts were last scaled), and loses
// estimates where either has drifted:
// - Magnification. When the eye turns a surface towards itself or comes closer, last frame's
//   pixels each covered more of it than this frame's do: a converged value is then the mean
//   of fewer patterns per pixel of surface, interpolated between texels that lie further apart
//   on it. Without this, a surface first seen edge-on (eq 3's threshold grows as 1 / cos, so
//   its few grazing pixels pass the test) kept their values, stretched over the many pixels it
//   covers later, as converged (docs/results/DECISIONS.md, orbit-lag). The per-frame
//   area ratios multiply (minification pays back, down to 1); past MAGNIFICATION_LIMIT the
//   counts are divided by the product and it restarts at 1. Carried rather than applied each
//   frame: counts are whole numbers (they index patterns), and a camera step of a fraction of
//   a pixel must not cost an estimate anywhere.
// - Displacement. Resampling in screen space is exact for a plane but not for a curved
//   surface, least of all near a silhouette, where the surface point varies fastest across
//   the screen: frame after frame the value drifts from the point it belongs to (on the
//   box:bunny orbit by one to several pixels over most of the model, and the indirect light's
//   gradients turned into an embossed error). The carried point, projected with this frame's
//   camera, lands `e` pixels from the pixel's centre; past DISPLACEMENT_LIMIT the counts are
//   divided by 2e, so that the fresh estimates that make the count whole again leave at most
//   half a pixel of it, and the point restarts at the pixel's.
// An accumulating pixel merges one fresh estimate at its own point this frame: its carried
// point moves there by the running mean's weight.
const float MAGNIFICATION_LIMIT = 1.1;
const float DISPLACEMENT_LIMIT = 1.0; // pixels

// Where world point q lies on the screen of the camera `view_proj`, in pixels (eq 1 with last
// frame's camera; with this frame's, where a carried registration point lands now); false for
// a point behind the eye.
bool to_screen(mat4 view_proj, vec3 q, out vec2 f) {
    vec4 c = view_proj * vec4(q, 1.0);
    f = c.w > 0.0 ? (c.xy / c.w * 0.5 + 0.5) * vec2(frame.size) : vec2(0.0);
    return c.w > 0.0; // false for NaN too
}
// Work blocks (quadrants of the 16x16 group) that hold pixels needing work, the pixels with no
// history, and those a moving object took it from, per lane.
shared uint quadrant_mask[LANES];
shared uint group_disoccluded[LANES];
shared uint group_invalidated[LANES];
// Lanes listing single pixels (block shift 0): the group's new and accumulating pixels, and
// where its run starts in the lane's list.
shared uint group_listed[LANES];
shared uint group_list_base[LANES];

// Where a moving object changes a lane's value: MOVED_* of shared_constants.glsl, tested
// against the box around every object that moved, at its last and its new place.

// Distance from p to the moved box (0 inside).
float moved_distance(vec3 p) {
    return length(max(max(frame.moved_min - p, p - frame.moved_max), vec3(0.0)));
}

// Whether a screen-space estimate with world radius `radius` at p, whose taps reach `pad_px`
// pixels further (coarse position levels' blocks), can read a pixel of the moved box's screen
// footprint. Its taps read the G-buffer wherever points within the radius
// of p project (the thesis's steps go as far as the radius projected at p's depth, Mittring's
// and Szentandrasi's points are nearer the eye by up to the radius): so within the radius
// projected at (depth - radius), with a floor of a tenth of the depth (a closer eye grows the
// reach to most of the screen), plus the coarsest position level's block (far taps) and a
// pixel. No hard cut at the radius in world space: a tap that lands on the moved object in
// front counts, only attenuated.
bool moved_on_screen(vec3 p, float radius, float pad_px) {
    float depth = max((frame.view_proj * vec4(p, 1.0)).w, 1e-30);
    float near = max(depth - radius, 0.1 * depth);
    float grow = radius * float(frame.size.y) / (2.0 * frame.tan_half_fov * near) +
                 pad_px + 1.0;
    vec2 c = vec2(gl_GlobalInvocationID.xy) + 0.5;
    vec4 r = frame.moved_screen_rect;
    return all(greaterThanEqual(c, r.xy - grow)) && all(lessThanEqual(c, r.zw + grow));
}

// Whether what moved this frame reaches the value of a lane with reach `reach` (MOVED_* in its
// low 8 bits; for MOVED_SCREEN, the taps' extra pixels above them, and sampling radius
// `reach_radius` relative to the scene's) at p. The
// shadow footprint is widened by the PCF kernel (pcf_radius texels, and two for the tap's
// bilinear reach and rounding): a shadow test there may meet the moved object, one outside it
// cannot.
bool moved_reaches(uint reach, float reach_radius, vec3 p) {
    uint mode = reach & 0xffu;
    if (frame.moved_count == 0u || mode == 0u) return false;
    float d = moved_distance(p);
    if (mode == MOVED_SCREEN) {
        float pad_px = float(reach >> 8);
        return d <= 0.0 || moved_on_screen(p, reach_radius * frame.scene_radius, pad_px);
    }
    if (d <= 0.0) return true;
    if (mode != MOVED_SHADOW) return false;
    vec4 c = frame.light_view_proj * vec4(p, 1.0);
    if (!(c.w > 0.0)) return false; // behind the light: unlit whatever moves
    vec2 t = (c.xy / c.w * 0.5 + 0.5) * frame.shadow_map_size;
    float grow = frame.pcf_radius + 2.0;
    vec4 r = frame.moved_light_rect;
    return all(greaterThanEqual(t, r.xy - grow)) && all(lessThanEqual(t, r.zw + grow));
}

bool tap_valid(ivec2 t, vec3 p, vec3 n, float eps) {
    if (outside_frame(t)) return false;
    vec4 h = texelFetch(prev_position, t, 0);
    return h.w != 0.0 && distance(h.xyz, p) <= eps && // eq 3
           dot(texelFetch(prev_normal, t, 0).xyz, n) >= FACING_ACCEPT;
}

// Eqs 1-3 for `pixel`. Where all four taps around the previous position hold this surface,
// each lane reads their bilinear blend or one of them (pick_registered), else the nearest
// texel. A static camera (decided on the CPU) reuses the texel itself where nothing moved:
// eq 1's rounding noise would otherwise blend neighbours into a converged value every frame,
// and that noise grows with the coordinates' distance from the origin. On a moving object eq 1
// and eq 3 take the point where it was last frame (p minus the G-buffer's motion): its history
// follows it, and what it uncovered finds the object gone from its previous texel.
Reprojected reproject(ivec2 pixel) {
    Reprojected r;
    r.geometry = false;
    r.found = false;
    r.bilinear = false;
    r.nearest = pixel;
    r.base = pixel;
    r.w = vec2(0.0);
    r.stretch = 1.0;
    r.p = vec3(0.0);
    r.motion = vec3(0.0);
    vec4 position = texelFetch(g_position, pixel, 0);
    if (position.w == 0.0) return r;
    r.geometry = true;
    r.p = position.xyz;
    r.motion = texelFetch(g_motion, pixel, 0).xyz;
    // Where the surface point was: the point itself for what stands still (motion exactly 0).
    vec3 p = r.p - r.motion;
    bool still = frame.camera_static != 0u && r.motion == vec3(0.0);
    vec2 f;
    if (!to_screen(frame.prev_view_proj, p, f)) return r; // eq 1
    if (still) f = vec2(pixel) + 0.5;
    r.nearest = texel_of(f, vec2(frame.size));
    f = clamp(f, vec2(-1.0), vec2(frame.size) + 1.0);
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float eps = disocclusion_epsilon(p, n);
    r.found = tap_valid(r.nearest, p, n, eps); // eqs 2-3 on the nearest texel
    if (!r.found || still) return r; // an unmoved eye on an unmoved surface: stretch 1
    float now = surface_footprint(r.p, n, frame.camera_pos);
    float before = surface_footprint(p, n, frame.prev_camera_pos);
    // Footprints are positive (distance > 0 past eq 1's w > 0 test); the ratio is finite.
    r.stretch = now > 0.0 ? (before / now) * (before / now) : 1.0;
    vec2 g = f - 0.5;
    r.base = ivec2(floor(g)); // f is clamped to [-1, size + 1]: defined conversion
    r.w = g - vec2(r.base);
    r.bilinear = true;
    for (int k = 0; k < 4 && r.bilinear; ++k)
        r.bilinear = tap_valid(r.base + ivec2(k & 1, k >> 1), p, n, eps);
    return r;
}

// The estimates a bilinear blend of means holds: a mean of n_i estimates has variance
// sigma^2 / n_i, the blend sum w_i^2 sigma^2 / n_i, which is the variance of a mean of
// 1 / sum(w_i^2 / n_i) estimates. Capped at the strongest tap (the blend's spatial averaging
// is not counted as more patterns) and floored to a whole number (counts index patterns).
// Taking the weakest tap instead, as before, let one young tap make its three converged
// neighbours' blend young again: under motion young counts spread along the flow every frame,
// and a third of a slowly orbiting view stayed accumulating with a hundred disocclusions per
// frame. A tap of 0 estimates (never the case for a valid history texel) gives 0.
// The cap is also what keeps the cache cheap under motion, at a price: a tap that lost
// estimates to the magnification or displacement rule takes them back from a stronger
// neighbour as soon as the blend spreads its weight, so it is not re-estimated and the blend's
// smoothing persists. Capped at the taps' weighted mean count instead, the cached indirect
// light ends much nearer its converged estimator, but most low-resolution samples are then
// gathered every frame, nearly twice the gather's time (figures: docs/results/DECISIONS.md,
// "The reprojection's count credit and history resampling").
float blend_count(vec4 n, vec4 w) {
    vec4 inv = mix(vec4(1.0e30), 1.0 / max(n, vec4(1e-30)), greaterThan(n, vec4(0.0)));
    float spread = dot(w * w, mix(inv, vec4(0.0), equal(w, vec4(0.0))));
    float strongest = max(max(n.x, n.y), max(n.z, n.w));
    return spread > 0.0 ? min(floor(1.0 / spread), strongest) : strongest;
}

// Re-accumulation (--reaccumulate, RenderConfig::temporal): when the camera stops, every
// reused history restarts its pattern count and takes the rotation limit's L patterns afresh,
// while the value the motion left (O, which the bilinear resampling above smoothed frame
// after frame) fades out one L-th per frame: after n patterns the pixel shows
//     D_n = O (L - n) / L + (x_0 + ... + x_{n-1}) / L,
// which at n = L is the mean of the patterns, the value a render from scratch converges to,
// whatever O was; each frame changes it by (x_n - O) / L, a pattern's share, so nothing pops.
// The effects merge as always (the gated running mean, temporal.glsl): this pass hands them
// V = (L D_n - O) / (L - 1) holding L - 1 estimates, whose merge with x_n is exactly D_{n+1}.
// O rides in the registration (xyz), which a still camera does not need, and its w marks the
// pixel as re-accumulating: -(1 + the pattern count it had before). Should the camera (or the
// surface) move before L frames, the pixel keeps D_n with its old count, and its registration
// restarts at the surface point last frame's texel showed.
bool reaccumulating(vec4 registration) {
    return registration.w < 0.0;
}

// No floor on a tap's count (resample's `floors`).
const float NO_FLOOR = -1.0e30;

// Registration texel `t` for resampling under motion. A re-accumulation the motion interrupts
// restarts at the surface point the texel showed, and `before` gets the pattern count its
// history had before (the floor of that tap's count; NO_FLOOR where none ran).
vec4 registration_tap(texture2D registration_prev, ivec2 t, out float before) {
    vec4 v = texelFetch(registration_prev, t, 0);
    before = NO_FLOOR;
    if (!reaccumulating(v)) return v;
    before = -v.w - 1.0;
    return vec4(texelFetch(prev_position, t, 0).xyz, 1.0);
}

// Point resampling (--history-resample point; HISTORY_RESAMPLE_POINT): where all four taps
// hold the surface, the history is read from the one whose carried registration point,
// projected with this frame's camera, lands nearest the pixel's centre (value, counts and point
// together). The bilinear blend (the default) mixes neighbouring values again every frame,
// invisibly to the displacement rule (the blended point stays on the surface), and the mix
// grows with the history's age: this choice keeps the estimator's own converged value (the
// no-reuse level) where the blend drifts from it. But the blend's smoothing brings it nearer
// the ground truth, and since counts no longer borrow from neighbours here, more pixels
// accumulate and the cache loses most of its speed-up (figures: docs/results/DECISIONS.md,
// "The reprojection's count credit and history resampling").
Reprojected pick_registered(Reprojected r, texture2D registration_prev) {
    if (!r.bilinear || frame.history_resample != HISTORY_RESAMPLE_POINT) return r;
    vec2 centre = vec2(gl_GlobalInvocationID.xy) + 0.5;
    float best = 1.0e30;
    for (int k = 0; k < 4; ++k) {
        ivec2 t = r.base + ivec2(k & 1, k >> 1);
        vec2 s;
        float before;
        vec4 reg = registration_tap(registration_prev, t, before);
        if (!to_screen(frame.view_proj, reg.xyz, s)) continue;
        vec2 d = s - centre;
        float d2 = dot(d, d);
        if (d2 < best) { // false for NaN: such a tap is never picked
            best = d2;
            r.nearest = t;
        }
    }
    // Where no tap's point projects (all behind the eye), r.nearest stays the texel nearest
    // the previous position, and the displacement rule takes its estimates away.
    r.bilinear = false;
    return r;
}

// The bilinear blend of the four taps around the previous position (lower-left, right, up,
// up-right).
vec4 bilerp(Reprojected r, vec4 t00, vec4 t10, vec4 t01, vec4 t11) {
    return mix(mix(t00, t10, r.w.x), mix(t01, t11, r.w.x), r.w.y);
}

// A lane's texture at the previous position: the bilinear blend, or the nearest texel (its
// taps' a raised to at least `floors`, in tap order: x the nearest or lower-left, y right, z
// up, w up-right); `counted` holds, in the channel `channel`, the estimates the blend holds
// (blend_count of the taps' values in that channel).
vec4 resample(Reprojected r, texture2D t, int channel, vec4 floors, out float counted) {
    if (!r.bilinear) {
        vec4 v = texelFetch(t, r.nearest, 0);
        v.a = max(v.a, floors.x);
        counted = v[channel];
        return v;
    }
    vec4 t00 = texelFetch(t, r.base, 0);
    vec4 t10 = texelFetch(t, r.base + ivec2(1, 0), 0);
    vec4 t01 = texelFetch(t, r.base + ivec2(0, 1), 0);
    vec4 t11 = texelFetch(t, r.base + ivec2(1, 1), 0);
    t00.a = max(t00.a, floors.x);
    t10.a = max(t10.a, floors.y);
    t01.a = max(t01.a, floors.z);
    t11.a = max(t11.a, floors.w);
    vec4 w = vec4((1.0 - r.w.x) * (1.0 - r.w.y), r.w.x * (1.0 - r.w.y), (1.0 - r.w.x) * r.w.y,
                  r.w.x * r.w.y);
    counted = blend_count(vec4(t00[channel], t10[channel], t01[channel], t11[channel]), w);
    return bilerp(r, t00, t10, t01, t11);
}

// The registration at the previous position under motion, as `resample` blends it, each tap
// read once through registration_tap; `floors` gets the taps' counts from before an
// interrupted re-accumulation, for the history's resample.
vec4 resample_registration(Reprojected r, texture2D registration_prev, out vec4 floors) {
    if (!r.bilinear) {
        vec4 v = registration_tap(registration_prev, r.nearest, floors.x);
        floors.yzw = floors.xxx;
        return v;
    }
    vec4 t00 = registration_tap(registration_prev, r.base, floors.x);
    vec4 t10 = registration_tap(registration_prev, r.base + ivec2(1, 0), floors.y);
    vec4 t01 = registration_tap(registration_prev, r.base + ivec2(0, 1), floors.z);
    vec4 t11 = registration_tap(registration_prev, r.base + ivec2(1, 1), floors.w);
    return bilerp(r, t00, t10, t01, t11);
}

// A pixel is converged once it holds the rotation limit's patterns and, with the gated mean,
// once the mean itself holds that many: a restart (temporal.glsl's gate) empties the mean but
// not the pattern count, and a restart two patterns before the limit would otherwise freeze a
// mean of two estimates, the first chosen for being far from the old mean
// (tests/convergence.rs `late_restart_converges_like_a_render_from_scratch`: 0.065 RMSE from
// the reference against 0.0066 from scratch). A mean that keeps restarting keeps
// accumulating: a change is still going on there.
bool converged(float patterns, float in_mean) {
    float limit = float(frame.rotation_limit);
    return patterns >= limit && (frame.accumulate_mode != ACCUMULATE_GATED || in_mean >= limit);
}

bool in_rect(ivec2 pixel, uvec4 rect) {
    return all(greaterThanEqual(uvec2(pixel), rect.xy)) && all(lessThan(uvec2(pixel), rect.zw));
}

// What a lane's pixel takes from the frame: its push constants' lane (active, history_valid,
// block shift, moving objects' reach), the reach's sampling radius, whether the pixel is in the
// lane's refresh tile, and whether the lane starts or stops re-accumulating this frame.
struct LaneInput {
    uvec4 lane;
    float reach_radius;
    bool refreshed;
    bool start;
    bool stop;
};

// What it writes: the state, the resampled history, moments and registration, and whether a
// moving object took the history.
struct LaneOutput {
    uint state;
    vec4 history;
    vec4 moments;
    vec4 registration;
    bool invalidated;
};

// One lane's history, moments, registration and state from last frame's images. The history's
// pattern count (a) and the moments' count of estimates in the gated mean (z) are the blend's
// (blend_count), divided where the registration says the value has been magnified or displaced
// (at least one estimate stays: the value is not thrown away). A pixel in the refresh tile
// (`refreshed`) is recomputed at its own point this frame, as is a new one: their registration
// restarts.
LaneOutput lane_state(Reprojected r, LaneInput lane_in, texture2D history_prev,
                      texture2D moments_prev, texture2D registration_prev) {
    uvec4 lane = lane_in.lane;
    bool refreshed = lane_in.refreshed;
    bool start = lane_in.start;
    bool stop = lane_in.stop;
    vec4 history = vec4(0.0);
    vec4 moments = vec4(0.0);
    vec4 registration = vec4(r.p, 1.0);
    bool invalidated = false;
    if (!r.geometry)
        return LaneOutput(STATE_BACKGROUND, history, moments, registration, invalidated);
    uint state = STATE_NEW;
    invalidated = lane.y != 0u && r.found && moved_reaches(lane.w, lane_in.reach_radius, r.p);
    if (lane.y != 0u && r.found && !invalidated) {
        r = pick_registered(r, registration_prev);
        // An unmoved eye on an unmoved surface: the texel itself, as it is.
        bool still = frame.camera_static != 0u && r.motion == vec3(0.0);
        // Still: the pixel's own registration, as it is (a re-accumulation's marker kept).
        vec4 held = still ? texelFetch(registration_prev, r.nearest, 0) : vec4(0.0);
        vec4 floors = vec4(NO_FLOOR);
        registration = still ? held : resample_registration(r, registration_prev, floors);
        float counted;
        history = resample(r, history_prev, 3, floors, counted);
        history.a = counted;
        moments = resample(r, moments_prev, 2, vec4(NO_FLOOR), counted);
        moments.z = counted;
        registration.xyz += r.motion; // the carried point moves with its object
        float magnification = max(registration.w * r.stretch, 1.0);
        float loss = 1.0;
        if (magnification > MAGNIFICATION_LIMIT) {
            loss = magnification;
            magnification = 1.0;
        }
        // A static camera reuses each texel of still geometry as is (no drift), and its eq 1
        // is not evaluated there: far from the origin the projection's rounding alone can move
        // a point a pixel. A carried point behind the eye counts as displaced beyond any limit.
        vec2 s;
        float e = 0.0;
        if (frame.camera_static == 0u || r.motion != vec3(0.0))
            e = to_screen(frame.view_proj, registration.xyz, s)
                    ? distance(s, vec2(gl_GlobalInvocationID.xy) + 0.5)
                    : 1.0e9;
        if (e > DISPLACEMENT_LIMIT) {
            loss *= 2.0 * e;
            registration.xyz = r.p;
        }
        if (loss > 1.0) {
            history.a = max(floor(history.a / loss), min(history.a, 1.0));
            moments.z = max(floor(moments.z / loss), min(moments.z, 1.0));
        }
        registration.w = magnification;
        state = converged(history.a, moments.z) ? STATE_CONVERGED : STATE_ACCUMULATING;
        if (state == STATE_ACCUMULATING)
            registration.xyz = mix(registration.xyz, r.p, 1.0 / (history.a + 1.0));
        float limit = float(frame.rotation_limit);
        bool marked = still && reaccumulating(held);
        bool going = marked && !stop;
        if (marked && stop) {
            // A change reached the values: the fade ends and the gated mean runs as on any
            // still view, so the gate sees the change (the fade zeroes its pending crossing
            // every frame, and a moved light lagged by the fade's L frames).
            registration = vec4(r.p, 1.0);
        } else if (going && history.a >= limit) {
            registration = vec4(r.p, 1.0); // done: the mean of L fresh patterns
        } else if (still && !refreshed && limit >= 2.0 && (going || (start && !stop))) {
            vec3 o = going ? held.xyz : history.rgb;
            registration = going ? held : vec4(o, -1.0 - history.a);
            if (!going) history.a = 0.0;
            // D_n -> V: the merge with this frame's pattern gives D_{n+1}. No gate crossing
            // carries over (y = 0): the value changes by design, and a crossing needs two
            // frames in a row.
            history.rgb = (limit * history.rgb - o) / (limit - 1.0);
            moments.yz = vec2(0.0, limit - 1.0);
            state = STATE_ACCUMULATING;
        }
    }
    if (refreshed) registration = vec4(r.p, 1.0);
    return LaneOutput(state, history, moments, registration, invalidated);
}

bool needs_work(uint state) {
    return state == STATE_NEW || state == STATE_ACCUMULATING || state == STATE_REFRESH;
}

// The lane's images at `pixel` and its group tallies. Lanes are macros over k because each
// lane's images are bindings of their own (their formats differ by effect, so no binding array
// can hold them, and GLSL cannot index separate bindings by a variable).
#define LANE_PIXEL(k)                                                                          \
    if (lanes.lane_##k.x != 0u) {                                                              \
        LaneInput lane_in;                                                                     \
        lane_in.lane = lanes.lane_##k;                                                         \
        lane_in.reach_radius = lanes.reach_radius[k];                                          \
        lane_in.refreshed = r.geometry && in_rect(pixel, lanes.refresh_rect_##k);              \
        lane_in.start = (lanes.reaccumulate.x >> k & 1u) != 0u;                                \
        lane_in.stop = (lanes.reaccumulate.y >> k & 1u) != 0u;                                 \
        LaneOutput o = lane_state(r, lane_in, history_prev_##k, moments_prev_##k,              \
                                  registration_prev_##k);                                      \
        if (o.invalidated) atomicAdd(group_invalidated[k], 1u);                                \
        else if (o.state == STATE_NEW) atomicAdd(group_disoccluded[k], 1u);                    \
        if (lane_in.refreshed) o.state = STATE_REFRESH;                                        \
        imageStore(history_cur_##k, pixel, o.history);                                         \
        imageStore(moments_cur_##k, pixel, o.moments);                                         \
        imageStore(registration_cur_##k, pixel, o.registration);                               \
        imageStore(state_out_##k, pixel, uvec4(o.state));                                      \
        if (needs_work(o.state)) atomicOr(quadrant_mask[k], quadrant_bit);                     \
        if (lanes.lane_##k.z == 0u && (o.state == STATE_NEW || o.state == STATE_ACCUMULATING)) \
            list_slot[k] = atomicAdd(group_listed[k], 1u);                                     \
    }

// Work block `q` of this group in the lane's list: 16x16 blocks are the whole group (q = 0
// stands for any quadrant), 8x8 blocks each quadrant.
uvec2 listed_block(uint q, uint shift) {
    uvec2 group = gl_WorkGroupID.xy;
    return shift == 4u ? group : group * 2u + uvec2(q & 1u, q >> 1);
}

uint listed_quadrants(uint mask, uint shift) {
    return shift == 4u ? uint(mask != 0u) : mask;
}

// A work list's indirect dispatch: `groups` workgroups as x * y, x at most frame.max_groups_x
// (the device's maxComputeWorkGroupCount[0], at least Vulkan's 65,535; a test hook lowers
// it), y growing beyond it (every device takes 65,535 in y: MAX_SIZE's 8x8 blocks need 64).
// Consumers index group y * x + x (effect.glsl's listed_group) and skip groups past the list.
// (A macro: atomics need the buffer's members themselves, not copies.)
#define LIST_DISPATCH(counters, groups)                                                        \
    {                                                                                          \
        uint most = max(frame.max_groups_x, 1u);                                               \
        atomicMax(counters.dispatch_x, min(groups, most));                                     \
        atomicMax(counters.dispatch_y, (groups + most - 1u) / most);                           \
    }

#define LANE_LIST(k)                                                                           \
    if (lanes.lane_##k.x != 0u) {                                                              \
        if (group_disoccluded[k] > 0u)                                                         \
            atomicAdd(counters_##k.disoccluded_pixels, group_disoccluded[k]);                  \
        if (group_invalidated[k] > 0u)                                                         \
            atomicAdd(counters_##k.invalidated_pixels, group_invalidated[k]);                  \
        uint shift = lanes.lane_##k.z;                                                         \
        if (shift == 0u) {                                                                     \
            uint n = group_listed[k];                                                          \
            uint base = n > 0u ? atomicAdd(counters_##k.listed_pixels, n) : 0u;                \
            group_list_base[k] = base;                                                         \
            if (n > 0u)                                                                        \
                LIST_DISPATCH(counters_##k, (base + n + 63u) / 64u)                            \
        }                                                                                      \
        uint mask = listed_quadrants(quadrant_mask[k], shift);                                 \
        uint blocks = shift != 0u ? bitCount(mask) : 0u;                                       \
        if (blocks > 0u) {                                                                     \
            uint slot = atomicAdd(counters_##k.listed_blocks, blocks);                         \
            LIST_DISPATCH(counters_##k, slot + blocks)                                         \
            for (uint q = 0u; q < 4u; ++q) {                                                   \
                if ((mask & (1u << q)) == 0u) continue;                                        \
                uvec2 b = listed_block(q, shift);                                              \
                counters_##k.data[slot++] = b.x | (b.y << 16);                                 \
            }                                                                                  \
        }                                                                                      \
    }

// This pixel's entry in each pixel-listing lane's run (NOT_LISTED: none).
const uint NOT_LISTED = 0xffffffffu;
uint list_slot[LANES];

#define LANE_WRITE(k)                                                                          \
    if (list_slot[k] != NOT_LISTED)                                                            \
        counters_##k.data[group_list_base[k] + list_slot[k]] = uint(pixel.x) | (uint(pixel.y) << 16);

void main() {
    if (gl_LocalInvocationIndex < uint(LANES)) {
        quadrant_mask[gl_LocalInvocationIndex] = 0u;
        group_disoccluded[gl_LocalInvocationIndex] = 0u;
        group_invalidated[gl_LocalInvocationIndex] = 0u;
        group_listed[gl_LocalInvocationIndex] = 0u;
    }
    for (int k = 0; k < LANES; ++k) list_slot[k] = NOT_LISTED;
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!outside_frame(pixel)) {
        Reprojected r = reproject(pixel);
        uvec2 q = gl_LocalInvocationID.xy / 8u;
        uint quadrant_bit = 1u << (q.y * 2u + q.x);
        LANE_PIXEL(0)
#if LANES > 1
        LANE_PIXEL(1)
#endif
#if LANES > 2
        LANE_PIXEL(2)
#endif
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        LANE_LIST(0)
#if LANES > 1
        LANE_LIST(1)
#endif
#if LANES > 2
        LANE_LIST(2)
#endif
    }
    barrier();
    LANE_WRITE(0)
#if LANES > 1
    LANE_WRITE(1)
#endif
#if LANES > 2
    LANE_WRITE(2)
#endif
}
