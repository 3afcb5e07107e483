// Reverse reprojection (Lin 2013 eqs 1-3) and accumulation (eqs 4-5 and alternatives),
// shared by every effect with a history.
#ifndef TEMPORAL_GLSL
#define TEMPORAL_GLSL

#include "frame.glsl"

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

// Merge a fresh estimate into the reprojected history `old` that holds `n` estimates.
float accumulate(float old, float fresh, float n) {
    if (n < 0.5) return fresh;
    uint mode = frame.accumulate_mode;
    float k = frame.accumulate_param;
    if (mode == 0u) {
        // Eqs 4-5; values are in [0, 1], so saturate() keeps the difference's meaning.
        float confidence = 1.0 - clamp(abs(old - fresh), 0.0, 1.0) / (1.0 + k);
        return confidence * old + (1.0 - confidence) * fresh;
    }
    if (mode == 1u) return mix(old, fresh, k);
    return old + (fresh - old) / min(n + 1.0, max(k, 1.0));
}

// Eqs 4-5 for radiance: the difference is taken on values divided by the larger luminance of
// the two, so the confidence measures relative change and does not depend on the light's
// intensity (HDR values would otherwise always saturate eq 4).
vec3 accumulate3(vec3 old, vec3 fresh, float n) {
    if (n < 0.5) return fresh;
    uint mode = frame.accumulate_mode;
    float k = frame.accumulate_param;
    if (mode == 0u) {
        const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);
        float scale = max(max(dot(old, LUMA), dot(fresh, LUMA)), 1e-30);
        float confidence = 1.0 - clamp(length(old - fresh) / scale, 0.0, 1.0) / (1.0 + k);
        return confidence * old + (1.0 - confidence) * fresh;
    }
    if (mode == 1u) return mix(old, fresh, k);
    return old + (fresh - old) / min(n + 1.0, max(k, 1.0));
}

#endif // TEMPORAL_GLSL
