// SSAO estimators (GTAO's in gtao.glsl). Each returns occlusion in [0, 1] for one sampling pattern; `pattern` indexes
// the pattern sequences of patterns.glsl (rotation and range scale, or the sphere's points).
// The images they read are parameters, as XeGTAO passes its own: `position` (the G-buffer's)
// and `position_1..3` (ao_position_chain.comp's point-sampled levels), `normals`, and
// `rotations` (the 4x4 random vectors). The parameter block (ao_params.glsl) is the only
// resource the header declares.
#ifndef AO_GLSL
#define AO_GLSL

#include "frame.glsl"
#include "ao_params.glsl"
#include "shared_constants.glsl"
#include "patterns.glsl"
#include "hemisphere.glsl"

// log2 of the tap distance, in pixels, below which a tap reads the full-resolution G-buffer;
// each doubling beyond it reads one level coarser (XeGTAO's depth MIP offset, 3.3). A level-L
// texel's position lies at most 2^(L-1) px from the tap, under 1/19 of the tap's distance, so
// the tap's direction changes by at most about 3 degrees whatever the resolution.
const float AO_MIP_OFFSET = 3.3;

// Most steps per direction of the thesis estimator (AoConfig::directions_steps: 4 from 16
// samples up, else 2).
const uint AO_MAX_STEPS = 4u;

// The position level a tap `dist_px` pixels from the shaded pixel reads: 0, the
// full-resolution image, or with --ao-position-mips a point-sampled level for far taps, which
// keeps far taps of neighbouring pixels in a few cache lines.
uint ao_tap_level(float dist_px) {
    uint mips = ao.position_mips;
    if (mips == 0u || dist_px < exp2(AO_MIP_OFFSET + 1.0)) return 0u;
    return min(uint(log2(dist_px) - AO_MIP_OFFSET), mips);
}

// The G-buffer position a tap at `q_pixel`, `dist_px` pixels from the shaded pixel, reads.
vec4 ao_tap_position(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, ivec2 q_pixel, float dist_px) {
    uint level = ao_tap_level(dist_px);
    if (level == 0u) return texelFetch(position, q_pixel, 0);
    if (level == 1u) return texelFetch(position_1, q_pixel >> 1, 0);
    if (level == 2u) return texelFetch(position_2, q_pixel >> 2, 0);
    return texelFetch(position_3, q_pixel >> 3, 0);
}

// The full-resolution pixel whose position ao_tap_position returns: a level-L texel holds its
// centre pixel (ao_position_chain.comp), so a tap that also needs the surface's normal reads
// it there, not at `q_pixel`, whose surface may lie across a depth edge inside the block.
ivec2 ao_tap_pixel(ivec2 q_pixel, float dist_px) {
    int level = int(ao_tap_level(dist_px));
    if (level == 0) return q_pixel;
    ivec2 centre = ((q_pixel >> level) << level) + (1 << (level - 1));
    return min(centre, ivec2(frame.size) - 1);
}

// Per-pixel rotation from the 4x4 random-vector texture (unit 2D vectors).
vec2 ao_pixel_rotation(texture2D rotations, ivec2 pixel) {
    return texelFetch(rotations, pixel & 3, 0).xy;
}

vec2 rotate2(vec2 v, vec2 cs) {
    return vec2(cs.x * v.x - cs.y * v.y, cs.y * v.x + cs.x * v.y);
}

// Lin 2013 eq 6-8: directions x log-spaced screen-space steps; each sample q contributes
// max(n . (q - p)/|q - p|, 0) / D(d) with D(d) = 1 + a d + b d^2, d in units of the radius.
// The sum of taps [first, end) of the pattern (tap k: direction k / steps, step k % steps);
// over every tap, divided by their count, the estimate. Spread passes split a pattern's taps
// over lanes with it.
float ao_thesis_taps(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, texture2D rotations, ivec2 pixel, vec3 p, vec3 n,
                     uint pattern, uint first, uint end) {
    uint dirs = ao.directions;
    uint steps = ao.steps;
    float radius = ao.radius * frame.scene_radius;
    float inv_radius = 1.0 / radius;
    // View depth (clip w of a perspective projection): a sphere's projected size follows the
    // depth along the view axis, not the distance, which is larger towards the image corners.
    float depth = max((frame.view_proj * vec4(p, 1.0)).w, 1e-30);
    // The world radius projected to pixels at this depth; eq 8's far.
    float px_per_world = float(frame.size.y) / (2.0 * frame.tan_half_fov * depth);
    float near_px = ao.near_px;
    // At most a quarter of the image, at least 1.5 near steps; on images under 9 px the lower
    // bound wins (clamp with min > max is undefined in GLSL).
    float far_px = max(min(radius * px_per_world, 0.25 * float(frame.size.y)), near_px * 1.5);
    vec2 rotation_scale = ao_thesis_pattern(pattern, dirs);
    float scale = rotation_scale.y;
    float angle = rotation_scale.x;
    // The 4x4 random vectors perturb the pattern per pixel (the thesis's Figure 3.8 b).
    vec2 rot = rotate2(ao_pixel_rotation(rotations, pixel), vec2(cos(angle), sin(angle)));
    vec2 center = vec2(pixel) + 0.5;
    // Eq 8's steps are the same in every direction: computed once (pow is dear on a CPU
    // device), at most AO_MAX_STEPS of them (AoConfig::directions_steps).
    float step_px[AO_MAX_STEPS];
    for (uint i = 0u; i < steps; ++i)
        step_px[i] = ao_step_px(i, steps, near_px, far_px) * scale;
    // Directions 2 pi d / dirs, each the previous one turned by 2 pi / dirs: one sin/cos pair
    // per pixel instead of one per direction (the rounding this accumulates over even 1024
    // directions is below 1e-4 of a radian).
    vec2 turn = vec2(cos(TWO_PI / float(dirs)), sin(TWO_PI / float(dirs)));
    uint d0 = first / steps;
    // A range from direction 0 turns as the whole pattern does (the same sums bit for bit).
    vec2 dir = d0 == 0u ? rot : rotate2(rot, vec2(cos(TWO_PI * float(d0) / float(dirs)),
                                                  sin(TWO_PI * float(d0) / float(dirs))));
    float sum = 0.0;
    for (uint d = d0; d * steps < end; ++d, dir = rotate2(dir, turn)) {
        for (uint i = 0u; i < steps; ++i) {
            uint k = d * steps + i;
            if (k < first || k >= end) continue;
            float s = step_px[i];
            ivec2 q_pixel = ivec2(floor(center + dir * s));
            if (outside_frame(q_pixel))
                continue;
            vec4 q = ao_tap_position(position, position_1, position_2, position_3, q_pixel, s);
            if (q.w == 0.0) continue;
            vec3 v = q.xyz - p;
            float d2 = dot(v, v);
            // Same-point samples carry no direction: 1e-12 of the squared depth is far below
            // one pixel's footprint at any depth.
            if (d2 <= 1e-12 * depth * depth) continue;
            float len = sqrt(d2);
            float x = len * inv_radius;
            // max(n . v/|v|, 0) / D(x), with one division.
            sum += max(dot(n, v), 0.0) / (len * (1.0 + ao.atten_a * x + ao.atten_b * x * x));
        }
    }
    return sum;
}

// Mittring 2007: points in a sphere of the world radius around p; a point is occluded when
// the visible surface at its screen position is in front of it (within the radius). The
// points of patterns 0, 1, ... fill the ball uniformly (patterns.glsl), so the radius is not
// scaled per pattern: their radii already vary continuously.
// Occluded points among points [first, end) of the pattern.
float ao_crytek_taps(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, texture2D rotations, ivec2 pixel, vec3 p, uint pattern,
                     uint first, uint end) {
    uint count = ao.samples;
    float radius = ao.radius * frame.scene_radius;
    vec3 view_dir = safe_normalize(p - frame.camera_pos, vec3(0.0, 0.0, -1.0));
    vec3 t = safe_normalize(cross(view_dir, abs(view_dir.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0)), vec3(1, 0, 0));
    vec3 b = cross(view_dir, t);
    vec2 rot = ao_pixel_rotation(rotations, pixel);
    float occluded = 0.0;
    for (uint k = first; k < end; ++k) {
        vec3 o = crytek_offset(k, count, pattern);
        vec2 xy = rotate2(o.xy, rot);
        vec3 s = p + radius * (xy.x * t + xy.y * b + o.z * view_dir);
        vec4 clip = frame.view_proj * vec4(s, 1.0);
        if (clip.w <= 0.0) continue;
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        vec2 q_screen = uv * vec2(frame.size);
        ivec2 q_pixel = texel_of(q_screen, vec2(frame.size));
        if (outside_frame(q_pixel))
            continue;
        vec4 q = ao_tap_position(position, position_1, position_2, position_3, q_pixel, distance(q_screen, vec2(pixel) + 0.5));
        if (q.w == 0.0) continue;
        float scene_depth = (frame.view_proj * vec4(q.xyz, 1.0)).w;
        float gap = clip.w - scene_depth;
        // In front of the sample by more than 1e-4 of its depth (fp32 noise). The range check
        // allows 4 radii: along a grazing view ray a point just below a surface is several
        // radii behind it, and a tighter check would wrongly light flat ground.
        if (gap > 1e-4 * clip.w && gap < 4.0 * radius) occluded += 1.0;
    }
    return occluded;
}

// Szentandrasi section 3.1: K points p + r omega in the hemisphere around the normal (Halton
// directions, bases 2 and 5, and random steps r in [0, r_max)), back-projected; the occlusion
// is the fraction that lie behind the visible surface (hemisphere.glsl). Pattern j takes
// Halton indices j K .. j K + K - 1, so accumulated patterns continue one sequence.
float ao_szentandrasi_taps(texture2D position, texture2D normals, ivec2 pixel, vec3 p, vec3 n,
                           uint pattern, uint first, uint end) {
    uint count = ao.samples;
    float r_max = ao.radius * frame.scene_radius;
    float occluded = 0.0;
    for (uint k = first; k < end; ++k) {
        vec4 w = hemisphere_sample(pattern * count + k, pixel, n, r_max);
        if (hemisphere_tap(position, normals, p + w.w * w.xyz, r_max).occluded) occluded += 1.0;
    }
    return occluded;
}

#include "gtao.glsl"

// The estimator: a specialization constant (AoEstimator::code, constant 0 of the estimating
// passes), so a pipeline holds its own estimator's code and no other. Functions read it through
// a variable: glslang would turn a comparison of it into OpSpecConstantOp, which naga's
// reflection cannot read; the driver folds the branches once it is specialized.
layout(constant_id = 0) const uint AO_ESTIMATOR = AO_THESIS;

// Taps one pattern of the estimator reads (the work counters' evaluations; GTAO's unit is a
// slice: its two horizon searches).
uint ao_taps() {
    uint estimator = AO_ESTIMATOR;
    if (estimator == AO_THESIS) return ao.directions * ao.steps;
    if (estimator == AO_GTAO) return max(ao.directions, 1u);
    return ao.samples;
}

// The sum of taps [first, end) of pattern `pattern` of the estimator: over every tap
// (ao_taps()), divided by their count, that pattern's occlusion.
float ao_taps_sum(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, texture2D normals, texture2D rotations,
                  ivec2 pixel, vec3 p, vec3 n, uint pattern, uint first, uint end) {
    uint estimator = AO_ESTIMATOR;
    if (estimator == AO_CRYTEK)
        return ao_crytek_taps(position, position_1, position_2, position_3, rotations, pixel, p, pattern, first, end);
    if (estimator == AO_SZENTANDRASI)
        return ao_szentandrasi_taps(position, normals, pixel, p, n, pattern, first, end);
    if (estimator == AO_GTAO)
        return ao_gtao_taps(position, position_1, position_2, position_3, normals, pixel, p, n, pattern, first, end);
    return ao_thesis_taps(position, position_1, position_2, position_3, rotations, pixel, p, n, pattern, first, end);
}

// Occlusion averaged over `patterns` consecutive patterns starting at `first` (a whole number:
// pattern indices arrive as floats from the history's count channel, exact below 2^24).
float ao_estimate(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, texture2D normals, texture2D rotations,
                  ivec2 pixel, vec3 p, vec3 n, float first, uint patterns) {
    uint taps = ao_taps();
    float sum = 0.0;
    for (uint j = 0u; j < patterns; ++j)
        sum += ao_taps_sum(position, position_1, position_2, position_3, normals, rotations, pixel, p, n, uint(first) + j, 0u, taps) /
               float(taps);
    return sum / float(max(patterns, 1u));
}

#endif // AO_GLSL
