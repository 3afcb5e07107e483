// Percentage-closer filtering (Reeves et al. 1987) against the light view's depth. Requires
// `shadow_depth` to be declared by the including shader.

// Receiver in light space: shadow-map uv, view distance along the light axis, and a bias in the
// same units: the world size of one shadow texel at the receiver, grown with the slope of the
// surface to the light. Everything is proportional to depth, so the bias is scale-free.
struct Receiver {
    vec2 uv;
    float depth;
    float bias;
};

Receiver light_receiver(vec3 p, float cos_surface) {
    vec4 clip = frame.light_view_proj * vec4(p, 1.0);
    Receiver r;
    r.depth = clip.w;
    r.uv = clip.xy / max(clip.w, 1e-30) * 0.5 + 0.5;
    float texel_world = 2.0 * r.depth * frame.light_params.y / frame.light_params.z;
    float slope = sqrt(max(1.0 - cos_surface * cos_surface, 0.0)) / max(cos_surface, 0.1);
    r.bias = texel_world * (1.0 + min(slope, 10.0)) + 1e-5 * r.depth;
    return r;
}

// 1 when the texel at `offset` (in texels) from the receiver's projection sees the light.
// Outside the shadow map is outside the light frustum: the spot cone darkens it anyway, so it
// counts as lit and the cone alone shapes that edge.
float shadow_test(Receiver r, vec2 offset) {
    int size = int(frame.light_params.z);
    ivec2 texel = ivec2(floor(r.uv * float(size) + offset));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(size)))) return 1.0;
    float occluder = light_linear_depth(texelFetch(shadow_depth, texel, 0).r);
    return r.depth <= occluder + r.bias ? 1.0 : 0.0;
}

// k x k regular grid over +-radius texels (k = 1: hard shadow).
float pcf_grid(Receiver r, int k) {
    float radius = frame.light_params.w;
    float lit = 0.0;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i)
            lit += shadow_test(r, k > 1 ? (vec2(i, j) / float(k - 1) * 2.0 - 1.0) * radius : vec2(0.0));
    return lit / float(k * k);
}

// `count` samples of a Vogel spiral filling the disc of the PCF radius, rotated by `angle` and
// scaled by `scale` (the thesis rotates and scales the 9-sample pattern every frame).
float pcf_disc(Receiver r, uint count, float angle, float scale) {
    float radius = frame.light_params.w * scale;
    float lit = 0.0;
    for (uint j = 0u; j < count; ++j) {
        float rho = radius * sqrt((float(j) + 0.5) / float(count));
        float phi = float(j) * 2.39996322973 + angle;
        lit += shadow_test(r, rho * vec2(cos(phi), sin(phi)));
    }
    return lit / float(max(count, 1u));
}

// Range scale of shadow pattern j (1 for pattern 0, then +-10%).
float shadow_pattern_scale(float pattern) {
    return 1.0 + 0.2 * (fract(pattern * 0.6180339887 + 0.5) - 0.5);
}

// Visibility of world point p (normal n) with the configured kernel; `pattern` picks the disc's
// rotation and scale.
float shadow_visibility(vec3 p, vec3 n, float pattern) {
    vec3 l = safe_normalize(frame.light_pos.xyz - p, -frame.light_dir.xyz);
    float cos_surface = dot(n, l);
    if (cos_surface <= 0.0) return 0.0; // facing away: no direct light to shadow
    Receiver r = light_receiver(p, cos_surface);
    if (frame.ao_pattern.z > 0.5)
        return pcf_disc(r, frame.size.w, frame.ao_pattern.x * pattern, shadow_pattern_scale(pattern));
    return pcf_grid(r, int(frame.size.w));
}
