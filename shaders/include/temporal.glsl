// Reverse reprojection (Lin 2013 eqs 1-3) and accumulation (eqs 4-5 and alternatives),
// shared by every effect with a history.
#ifndef TEMPORAL_GLSL
#define TEMPORAL_GLSL

#include "frame.glsl"
#include "shared_constants.glsl"

// Per-pixel state written by the reprojection pass.
const uint STATE_CONVERGED = 0u;    // reused as is
const uint STATE_ACCUMULATING = 1u; // reused, one more pattern this frame
const uint STATE_NEW = 2u;          // disoccluded or first frame: computed from scratch
const uint STATE_REFRESH = 3u;      // in this frame's refresh tile: recomputed in full
const uint STATE_BACKGROUND = 4u;   // no geometry

// Eq 3 threshold at world point p with normal n. Relative mode: `scale` times the distance
// between neighbouring texels on this surface (pixel footprint at its depth over |cos| of the
// view angle), so it does not depend on scene units or depth. |cos| is floored at 0.1: beyond
// ~84 degrees a surface is a sliver and ten footprints is already lenient.
float disocclusion_epsilon(vec3 p, vec3 n) {
    if (frame.epsilon_absolute != 0u) return frame.epsilon;
    vec3 to_eye = frame.camera_pos - p;
    float dist = length(to_eye);
    float footprint = 2.0 * dist * frame.tan_half_fov / float(frame.size.y);
    float cos_view = abs(dot(n, to_eye / max(dist, 1e-30)));
    return frame.epsilon * footprint / max(cos_view, 0.1);
}

// Gate of the default mode (Accumulate::Gated, config.rs). The running mean restarts from the
// fresh estimate only when two consecutive estimates differ from the mean, on the same side, by
// more than `sigmas` standard deviations of the patterns so far AND by more than GATE_RELATIVE
// of the larger of the two luminances. One outlier is merged like any estimate (the mean stays
// unbiased: importance-sampled VPL gathers have heavy tails), a change of the lighting persists
// and restarts the mean one frame later. A restart empties the mean (the moments' count of
// estimates in it, z) but not the pixel's pattern count (the history's a), so a pixel whose
// mean keeps restarting (a grazing surface under fast motion, whose resampled history misses
// its steep gradient) still converges after the rotation limit and costs no more than with
// eqs 4-5. The relative floor is scale-free (HDR radiance and [0, 1] visibilities alike) and
// keeps one flipped PCF tap (1/9) or AO sample from counting as a change where every earlier
// pattern agreed (zero variance).
const float GATE_RELATIVE = 0.25;
// Estimates before the gate may act: with fewer the patterns' variance is not known yet.
const float GATE_MIN_COUNT = 4.0;
// Largest stored value: the squared luminance of the second moment stays finite in fp32.
const float HISTORY_MAX = 1.0e18;

// Weight of a fresh estimate in the merge with a history of `n` estimates (n >= 1); `change`
// is the thesis's |V_old - V_new| on the effect's own scale, `l_old` / `l_fresh` the
// luminances (the value itself for scalar effects). `moments` holds the mean squared luminance
// (x), the side of a pending gate crossing (y: +-1, 0 none) and the estimates in the gated
// mean (z), updated here for the gate. A weight of 1 restarts the mean from the fresh estimate.
float fresh_weight(float n, float change, float l_old, float l_fresh, inout vec4 moments) {
    uint mode = frame.accumulate_mode;
    float k = frame.accumulate_param;
    if (mode == ACCUMULATE_CONFIDENCE) return clamp(change, 0.0, 1.0) / (1.0 + k); // eqs 4-5
    if (mode == ACCUMULATE_EMA) return k;
    if (mode == ACCUMULATE_MEAN) return 1.0 / min(n + 1.0, max(k, 1.0));
    // ACCUMULATE_GATED:
    float sigma = sqrt(max(moments.x - l_old * l_old, 0.0));
    float gate = max(k * sigma, GATE_RELATIVE * max(abs(l_old), abs(l_fresh)));
    float diff = l_fresh - l_old;
    float in_mean = max(moments.z, 1.0);
    float side = in_mean >= GATE_MIN_COUNT && abs(diff) > gate ? sign(diff) : 0.0;
    // A resampled history blends the flags of its taps: a crossing counts where most agree.
    bool persists = side * moments.y > 0.5;
    moments.y = persists ? 0.0 : side;
    return persists ? 1.0 : 1.0 / (in_mean + 1.0);
}

// Whether a history of `n` patterns holds nothing. A re-accumulating pixel (reproject.comp)
// restarts its pattern count at 0 but keeps a value, which its gated mean counts as
// rotation limit - 1 estimates (moments.z): it is merged, not replaced.
bool history_empty(float n, vec4 moments) {
    return n < 0.5 && moments.z < 0.5;
}

// Moments after a merge with weight `w` of an estimate of squared luminance `l2`.
vec4 merged_moments(vec4 moments, float w, float l2) {
    moments.x += w * (l2 - moments.x);
    moments.z = w >= 1.0 ? 1.0 : moments.z + 1.0;
    return moments;
}

// Weight of a fresh scalar estimate (already clamped) merged into the history value `old`
// that holds `n` estimates: 1 for an empty history. `moments` (mean squared value, pending gate
// crossing, estimates in the mean) is updated in place; its w is left to the caller (0 after a
// restart from an empty history).
float merge_weight(float old, float n, float fresh, inout vec4 moments) {
    if (history_empty(n, moments)) {
        moments = vec4(fresh * fresh, 0.0, 1.0, 0.0);
        return 1.0;
    }
    float w = fresh_weight(n, abs(old - fresh), old, fresh, moments);
    moments = merged_moments(moments, w, fresh * fresh);
    return w;
}

// Merge a fresh scalar estimate into the history value `old` that holds `n` estimates;
// `moments` is updated in place (merge_weight). Returns (value, count).
vec2 accumulate(float old, float n, float fresh, inout vec4 moments) {
    // A non-finite estimate is dropped: the history and its moments stay as they were.
    if (!(abs(fresh) < FLOAT_MAX)) return vec2(old, n);
    fresh = clamp(fresh, -HISTORY_MAX, HISTORY_MAX);
    float w = merge_weight(old, n, fresh, moments);
    return vec2(old + w * (fresh - old), n + 1.0);
}

// The same for radiance. The thesis's difference is taken relative to the larger of the two
// values' norms, so confidence measures relative change for any colour and any intensity (a
// difference over luminance would be 14x larger for pure blue than for grey). Returns
// (value, count).
vec4 accumulate3(vec3 old, float n, vec3 fresh, inout vec4 moments) {
    // A non-finite estimate is dropped: the history and its moments stay as they were.
    if (!all_finite(fresh)) return vec4(old, n);
    fresh = clamp(fresh, vec3(-HISTORY_MAX), vec3(HISTORY_MAX));
    float l_fresh = dot(fresh, LUMA);
    if (history_empty(n, moments)) {
        moments = vec4(l_fresh * l_fresh, 0.0, 1.0, 0.0);
        return vec4(fresh, 1.0);
    }
    float norm = max(length(old), length(fresh));
    float change = norm > 0.0 ? length(old - fresh) / norm : 0.0;
    float w = fresh_weight(n, change, dot(old, LUMA), l_fresh, moments);
    moments = merged_moments(moments, w, l_fresh * l_fresh);
    return vec4(old + w * (fresh - old), n + 1.0);
}

// A refreshed pixel: the mean of every pattern is blended into the history with the refresh
// weight `w` (effect.glsl's refresh_weight). A history of `n` estimates, fewer than the rotation
// limit, weighs at most its share n / limit (a new pixel, n = 0, takes the mean alone).
// `mean2` is the patterns' mean squared luminance; the moments become the blend's, holding
// the rotation limit's count. Returns the weight of the recomputed mean.
float refresh_blend(float w, float n, float mean2, inout vec4 moments) {
    float limit = float(frame.rotation_limit);
    w = max(w, 1.0 - clamp(n / limit, 0.0, 1.0));
    moments = vec4(mix(moments.x, mean2, w), 0.0, limit, 0.0);
    return w;
}

#endif // TEMPORAL_GLSL
