// Percentage-closer filtering (Reeves et al. 1987) against the light view's depth. Requires
// `shadow_depth` to be declared by the including shader.
#ifndef SHADOW_GLSL
#define SHADOW_GLSL

#include "frame.glsl"
#include "patterns.glsl"

// Receiver in light space: shadow-map uv, view distance along the light axis (clip w), and the
// receiver's tangent plane in light clip space (point + two tangents), so each PCF tap can
// compare the occluder against the receiver plane's own depth on that texel's ray
// ("receiver plane depth bias"): a slanted receiver then does not shadow itself however wide
// the kernel is. What is left is a small bias for the curvature of real receivers and
// precision: one shadow texel's world size at the receiver, half of it grown with the
// slope. Everything is proportional to depth, so the bias is scale-free.
struct Receiver {
    vec2 uv;
    float depth;
    float bias;
    // Largest depth change the plane may claim between taps (guards rays that run nearly
    // parallel to the plane, where the intersection runs off to infinity).
    float reach;
    vec4 clip;
    vec4 tangent_clip;
    vec4 bitangent_clip;
};

Receiver light_receiver(vec3 p, vec3 n, float cos_surface) {
    Receiver r;
    r.clip = frame.light_view_proj * vec4(p, 1.0);
    r.depth = r.clip.w;
    r.uv = r.clip.xy / max(r.clip.w, 1e-30) * 0.5 + 0.5;
    float texel_world = 2.0 * r.depth * frame.light_tan_half_fov / frame.shadow_map_size;
    // tan of the angle between normal and light: depth change per texel of the plane.
    float tangent = sqrt(max(1.0 - cos_surface * cos_surface, 0.0)) / max(cos_surface, 0.01);
    r.bias = texel_world * (1.0 + 0.5 * min(tangent, 10.0)) + 1e-5 * r.depth;
    // The kernel's reach (its radius, diagonally, plus the texel rounding) along the plane,
    // up to 89.4 degrees; beyond that the cosine factor leaves no direct light to shadow.
    r.reach = texel_world * min(tangent, 100.0) * (1.5 * frame.pcf_radius + 2.0);
    vec3 t = normalize(cross(n, abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    r.tangent_clip = frame.light_view_proj * vec4(t, 0.0);
    r.bitangent_clip = frame.light_view_proj * vec4(cross(n, t), 0.0);
    return r;
}

// Depth the receiver is compared at for the light ray through shadow-map position `uv`: its
// tangent plane's depth on that ray (solve p + a t + b s = the ray in clip space for (a, b),
// take clip w) where the plane comes nearer the light than the receiver point, the point's own
// depth where it recedes. Nearer is where a slanted plane shadows itself (acne) and the plane
// fixes it exactly; where the plane recedes, the point's depth already passes the surface's
// own texels, and using the plane there would put taps beyond a convex edge (a box's rim)
// inside the solid and darken lit rims.
float receiver_plane_depth(Receiver r, vec2 uv) {
    vec2 ndc = uv * 2.0 - 1.0;
    vec2 col_a = r.tangent_clip.xy - ndc * r.tangent_clip.w;
    vec2 col_b = r.bitangent_clip.xy - ndc * r.bitangent_clip.w;
    vec2 rhs = ndc * r.clip.w - r.clip.xy;
    float det = col_a.x * col_b.y - col_a.y * col_b.x;
    float delta = 0.0;
    if (det != 0.0) {
        float a = (rhs.x * col_b.y - rhs.y * col_b.x) / det;
        float b = (col_a.x * rhs.y - col_a.y * rhs.x) / det;
        delta = a * r.tangent_clip.w + b * r.bitangent_clip.w;
        if (isnan(delta)) delta = 0.0;
    }
    return r.depth + clamp(delta, -r.reach, 0.0);
}

// 1 when the texel at `offset` (in texels) from the receiver's projection sees the light: the
// occluder depth stored for that texel (rasterised at its centre) against the receiver plane's
// depth on the same ray. Outside the shadow map is outside the light frustum: the spot cone
// darkens it anyway, so it counts as lit and the cone alone shapes that edge.
float shadow_test(Receiver r, vec2 offset) {
    int size = int(frame.shadow_map_size);
    ivec2 texel = texel_of(r.uv * float(size) + offset, vec2(size));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) return 1.0;
    float occluder = light_linear_depth(texelFetch(shadow_depth, texel, 0).r);
    float receiver = receiver_plane_depth(r, (vec2(texel) + 0.5) / float(size));
    return receiver <= occluder + r.bias ? 1.0 : 0.0;
}

// k x k regular grid over +-radius texels (k = 1: hard shadow).
float pcf_grid(Receiver r, int k) {
    float radius = frame.pcf_radius;
    float lit = 0.0;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i)
            lit += shadow_test(r, k > 1 ? (vec2(i, j) / float(k - 1) * 2.0 - 1.0) * radius : vec2(0.0));
    return lit / float(k * k);
}

// `count` taps of the Vogel spiral of pattern `pattern` at `pixel` over the PCF radius
// (pcf_disc_offset: over patterns the taps fill the disc uniformly).
float pcf_disc(Receiver r, uint count, uint pattern, ivec2 pixel) {
    float lit = 0.0;
    for (uint j = 0u; j < count; ++j)
        lit += shadow_test(r, frame.pcf_radius * pcf_disc_offset(j, count, pattern, pixel));
    return lit / float(max(count, 1u));
}

// Visibility of world point p (normal n) seen at `pixel` with the configured kernel; `pattern`
// (a whole number, carried as a float like the history's count) picks the disc's pattern.
// Shadow-map taps of one pattern (the work counters' evaluations).
uint shadow_taps() {
    return frame.pcf_kernel == 1u ? frame.pcf_count : frame.pcf_count * frame.pcf_count;
}

float shadow_visibility(vec3 p, vec3 n, float pattern, ivec2 pixel) {
    vec3 l = safe_normalize(frame.light_pos - p, -frame.light_dir);
    float cos_surface = dot(n, l);
    if (cos_surface <= 0.0) return 0.0; // facing away: no direct light to shadow
    Receiver r = light_receiver(p, n, cos_surface);
    if (frame.pcf_kernel == 1u)
        return pcf_disc(r, frame.pcf_count, uint(pattern), pixel);
    return pcf_grid(r, int(frame.pcf_count));
}

#endif // SHADOW_GLSL
