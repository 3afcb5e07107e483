// Ground-truth AO (Jimenez et al. 2016, "Practical Real-Time Strategies for Accurate Indirect
// Occlusion"; Intel's XeGTAO is the reference implementation): the hemisphere is cut into
// slices through the view vector; in each slice the two horizons are found by marching the
// G-buffer on both sides, and the cosine-weighted visibility between them is integrated in
// closed form (eq 10), weighted by the length of the normal projected on the slice. Over
// slices spread evenly in angle, the mean is the cosine-weighted visibility of the hemisphere
// (1 on an open plane for any view). Included by ao.glsl after its helpers.
//
// Relation to the ground truth (src/reference/estimators.rs): a sample farther than the radius
// R does not raise the horizon, so with attenuation (0, 0) GTAO estimates the reference's
// binary visibility within R exactly wherever the occluders are a height field as seen along
// each slice (a floor beside a wall: tests/gtao.rs). With eq 7's attenuation each rise of a
// horizon, from the sample at x = d/R, occludes the arc it covers by 1/D(x) (the rays of that
// arc meet the surface near that sample in a height field), where XeGTAO's falloff pulls the
// horizon towards the tangent plane: the arcs come closer to the ray-traced AO (figures:
// docs/results/DECISIONS.md, "GTAO's attenuation: weighted arcs, not XeGTAO's falloff"). Like
// every screen-space estimator it sees no occluder that is hidden or off screen, and it takes
// the visible surface for an infinitely thick one (the space behind it counts as occluded).
#ifndef GTAO_GLSL
#define GTAO_GLSL

// Steps are spread as ((i + jitter) / steps)^2 of the projected radius, XeGTAO's sample
// distribution power: denser near the pixel, where the horizon changes fastest.
const float GTAO_DISTRIBUTION_POWER = 2.0;

// acos on [-1, 1]; the clamp keeps a rounding past +-1 from giving NaN.
float gtao_acos(float x) {
    return acos(clamp(x, -1.0, 1.0));
}

// Eq 10's inner integral for one horizon angle h (from the view vector, signed towards the
// slice's direction) and the projected normal's angle n: (cos n + 2 h sin n - cos(2 h - n)) / 4.
float gtao_arc(float h, float n) {
    return (cos(n) + 2.0 * h * sin(n) - cos(2.0 * h - n)) * 0.25;
}

// Rank of the pixel in the 4x4 Bayer (ordered dither) matrix, 0-15: 0 8 2 10 / 12 4 14 6 /
// 3 11 1 9 / 15 7 13 5 down the rows.
float gtao_bayer(ivec2 pixel) {
    uint x = uint(pixel.x) & 3u, y = uint(pixel.y) & 3u;
    // Interleaving the bits of (x ^ y, y), low bit first: the recursive Bayer construction.
    uint xy = x ^ y;
    uint rank = ((xy & 1u) << 3) | ((y & 1u) << 2) | (xy & 2u) | ((y & 2u) >> 1);
    return float(rank);
}

// One side's visible arc (eq 10's inner integral) for a horizon of cosine `h` to the view
// vector, on the side `sign` (+1 towards the slice's direction, -1 away), the horizon kept
// within a quarter turn of the projected normal (angle n).
float gtao_side_arc(float h, float sign, float n) {
    float angle = sign * gtao_acos(h);
    return gtao_arc(n + clamp(angle - n, -HALF_PI, HALF_PI), n);
}

// The surface point the view ray through screen point `s` [px] meets: the plane of the
// G-buffer texel it falls in (position q, normal n_q). A texel's centre lies up to half a
// pixel off the slice's line, and its direction to the pixel then leaves the slice: on a plane
// seen at a grazing angle that alone raised horizons by 0.04 of visibility. False (and `hit`
// unset) where the ray grazes the texel's plane (within 3 degrees), whose intersection is
// ill-conditioned, or meets it behind the camera.
bool gtao_on_ray(vec2 s, vec3 q, vec3 n_q, vec3 right, vec3 down, vec3 forward, out vec3 hit) {
    vec2 ndc = s / vec2(frame.size) * 2.0 - 1.0;
    float aspect = float(frame.size.x) / float(frame.size.y);
    vec3 ray = forward + (ndc.x * aspect * frame.tan_half_fov) * right
             + (ndc.y * frame.tan_half_fov) * down;
    float along = dot(ray, n_q);
    hit = q;
    if (!(abs(along) > 0.05 * length(ray))) return false;
    float t = dot(q - frame.camera_pos, n_q) / along;
    if (!(t > 0.0)) return false;
    hit = frame.camera_pos + t * ray;
    return true;
}

// The sum over slices [first, end) of pattern `pattern` of (1 - the slice's visibility): over
// every slice (ao.directions), divided by their count, that pattern's occlusion. Pattern j
// turns every slice by the same angle (pattern_point's golden sequence), so any set of
// patterns keeps the slices evenly spread; the per-pixel rotation comes on top.
float ao_gtao_taps(texture2D position, texture2D position_1, texture2D position_2, texture2D position_3, texture2D normals, ivec2 pixel, vec3 p, vec3 n,
                   uint pattern, uint first, uint end) {
    uint slices = max(ao.directions, 1u);
    uint steps = max(ao.steps, 1u);
    float radius = ao.radius * frame.scene_radius;
    vec4 clip = frame.view_proj * vec4(p, 1.0);
    float depth = max(clip.w, 1e-30);
    float px_per_world = float(frame.size.y) / (2.0 * frame.tan_half_fov * depth);
    // The radius on screen, at least one step out of the pixel. Not capped at a quarter of the
    // image as the thesis estimator's: the step count is fixed, so a wider march costs no more
    // taps, and near a wall the cap hid occluders within the radius (figures:
    // docs/results/DECISIONS.md, "GTAO's uncapped radius and planar guard band"). At most 4
    // image heights, past which every tap is off the image.
    float radius_px = max(min(radius * px_per_world, 4.0 * float(frame.size.y)), ao.near_px);
    vec2 u = pattern_point(pattern);
    // The pixel's share of the slices' half turn: its rank in a 4x4 Bayer matrix, k / 16 of
    // the spacing between slices, so that the 16 pixels of a tile turn their slices to 16
    // evenly spread angles (a fixed pattern filtered over a 4x4 window sees 16 x slices
    // directions; random rotations clump) and neighbours differ by at least a quarter turn of
    // the spacing.
    float base = PI * (gtao_bayer(pixel) / 16.0 + u.x) / float(slices);
    vec3 v = safe_normalize(frame.camera_pos - p, n);
    // Camera right and image-down in world space: rows 0 and 1 of view_proj (no roll or
    // skew in a perspective projection's first two rows beyond the scale).
    vec3 right = safe_normalize(vec3(frame.view_proj[0][0], frame.view_proj[1][0], frame.view_proj[2][0]), vec3(1.0, 0.0, 0.0));
    vec3 down = safe_normalize(vec3(frame.view_proj[0][1], frame.view_proj[1][1], frame.view_proj[2][1]), vec3(0.0, -1.0, 0.0));
    // Row 3: the view depth (clip w) grows along the camera's forward axis.
    vec3 forward = safe_normalize(vec3(frame.view_proj[0][3], frame.view_proj[1][3], frame.view_proj[2][3]), -v);
    vec2 center = vec2(pixel) + 0.5;
    float inv_radius = 1.0 / radius;
    // Slices turn evenly about the view vector in the world (even screen angles would crowd
    // them off the image's centre, where the view ray leaves the camera axis: 0.004 of
    // visibility on an open plane): a basis perpendicular to v, and the screen direction of
    // each slice's world direction through the projection's derivative at p.
    vec3 a = safe_normalize(right - dot(right, v) * v, safe_normalize(cross(v, down), right));
    vec3 b = cross(v, a);
    // A shading normal facing away from the eye (smooth meshes near their silhouettes: the
    // two-sided normals keep such pixels) puts the view vector outside its hemisphere, where
    // eq 10's arcs, integrated from the view vector out, no longer cover the hemisphere: with
    // no occluder the slices' mean fell to 0.62 at 120 degrees and below 0 past 143. The
    // nearest normal whose hemisphere holds v, n less its part along v (perpendicular to v),
    // keeps the closed form exact: an unoccluded point's visibility is 1 at any angle.
    // XeGTAO's per-slice saturate of cos n overshoots instead (1.21 at 120 degrees).
    float n_dot_v = dot(n, v);
    if (n_dot_v < 0.0) n = safe_normalize(n - n_dot_v * v, a);
    float sum = 0.0;
    for (uint s = first; s < end; ++s) {
        float phi = base + PI * float(s) / float(slices);
        vec3 ortho = cos(phi) * a + sin(phi) * b;
        vec4 d_clip = frame.view_proj * vec4(ortho, 0.0);
        // The direction of d(clip.xy / clip.w) in pixels (the quotient rule; y grows down).
        vec2 d_screen = (d_clip.xy * clip.w - clip.xy * d_clip.w) * vec2(frame.size);
        float d_len = length(d_screen);
        // A direction the projection flattens to nothing (clip w near 0) marches nowhere:
        // its horizons stay at the tangent plane, an unoccluded slice.
        bool marches = d_len > 0.0;
        vec2 dir = marches ? d_screen / d_len : vec2(0.0);
        vec3 axis = cross(ortho, v);
        vec3 np = n - axis * dot(n, axis);
        float np_len = length(np);
        // A normal along the slice's axis: the projected normal, and so the slice's
        // visibility, is 0 (the closed form's limit; the other slices carry the weight).
        if (!(np_len > 1e-20)) {
            sum += 1.0;
            continue;
        }
        float cos_n = clamp(dot(np, v) / np_len, -1.0, 1.0);
        float sign_n = dot(ortho, np) < 0.0 ? -1.0 : 1.0;
        float ang_n = sign_n * gtao_acos(cos_n);
        // Per side (x: towards the slice's direction, y: away), the horizon's cosine to the
        // view vector, starting at the tangent plane.
        vec2 h = vec2(cos(ang_n + HALF_PI), cos(ang_n - HALF_PI));
        // Each side's visible arc: from the tangent plane's, each rise of the horizon takes
        // away the arc it covers, weighted by eq 7's attenuation of the sample that raised it
        // (outward, the rays between the old and the new horizon pass over every nearer sample
        // and meet the surface near this one). With attenuation (0, 0) every weight is 1 and
        // the sum is the arc below the final horizon, eq 10 exactly.
        vec2 arc = vec2(gtao_side_arc(h.x, 1.0, ang_n), gtao_side_arc(h.y, -1.0, ang_n));
        vec2 vis = arc;
        for (uint i = 0u; marches && i < steps; ++i) {
            float t = (float(i) + u.y) / float(steps);
            float s_px = max(radius_px * pow(t, GTAO_DISTRIBUTION_POWER), ao.near_px);
            for (int side = 0; side < 2; ++side) {
                vec2 offset = (side == 0 ? dir : -dir) * s_px;
                ivec2 q_pixel = ivec2(floor(center + offset));
                // Off the image (a planar guard band): the border texel's plane, met by the
                // ray through the tap, stands in for the surface beyond the edge; where that
                // ray misses it the tap is skipped (the texel itself lies off the slice). With
                // the uncapped radius the border's occluders count, which matters most on the
                // walkthroughs (figures: docs/results/DECISIONS.md, "GTAO's uncapped radius
                // and planar guard band").
                ivec2 inside = clamp(q_pixel, ivec2(0), ivec2(frame.size) - 1);
                bool off_image = inside != q_pixel;
                q_pixel = inside;
                if (q_pixel == pixel) continue;
                vec4 q = ao_tap_position(position, position_1, position_2, position_3, q_pixel, s_px);
                if (q.w == 0.0) continue;
                // The normal of the texel the position came from (a level's centre pixel).
                vec3 n_q = texelFetch(normals, ao_tap_pixel(q_pixel, s_px), 0).xyz;
                vec3 hit;
                if (!gtao_on_ray(center + offset, q.xyz, n_q, right, down, forward, hit) && off_image) continue;
                vec3 w = hit - p;
                float len = length(w);
                float x = len * inv_radius;
                if (!(len > 0.0) || x > 1.0) continue;
                float shc = dot(w, v) / len;
                // Eq 7's attenuation of a hit at x (1 with (0, 0)).
                float weight = 1.0 / (1.0 + ao.atten_a * x + ao.atten_b * x * x);
                if (shc > h[side]) {
                    float a = gtao_side_arc(shc, side == 0 ? 1.0 : -1.0, ang_n);
                    vis[side] -= weight * (arc[side] - a);
                    arc[side] = a;
                    h[side] = shc;
                }
            }
        }
        float visibility = np_len * (vis.x + vis.y);
        sum += 1.0 - visibility;
    }
    return sum;
}

#endif // GTAO_GLSL
