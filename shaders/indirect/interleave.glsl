// Geometry-aware reconstruction of the interleaved gather (Keller & Heidrich 2001; Segovia et
// al. 2006) inside one workgroup's tile of INTERLEAVE_TILE x INTERLEAVE_TILE pixels. Every
// pixel computed this frame gathers one share of the VPLs (rsm_gather). A new pixel (no
// history) takes the mean share of the pixels of the window around it that were computed this
// frame and lie on its surface (`same_surface`): the window holds every share with the same
// total weight, so on a continuous surface its first estimate sees the whole VPL set. A pixel
// with a history takes its own share: over N^2 frames it sees every share itself, so its
// accumulated mean converges to the whole gather with no spatial blur; the reconstruction's
// blur (the light's variation across the window) stays in the first of its estimates only.
// Requires INTERLEAVE_TILE and indirect_common.glsl.
#ifndef INTERLEAVE_GLSL
#define INTERLEAVE_GLSL

const uint INTERLEAVE_PIXELS = INTERLEAVE_TILE * INTERLEAVE_TILE;
shared vec4 interleave_share[INTERLEAVE_PIXELS]; // rgb: the pixel's share; a: 1 if computed
shared vec4 interleave_position[INTERLEAVE_PIXELS];
shared vec4 interleave_normal[INTERLEAVE_PIXELS];

// The estimate (rgb, a = its squared luminance) of the pixel at tile position `local` whose
// own share is `own`: reconstructed if `is_new`, else `own`. Every invocation of
// the workgroup calls it (it synchronises the workgroup); only `computed` pixels contribute,
// and only theirs is meaningful.
vec4 interleave_reconstruct(uvec2 local, bool computed, bool is_new, vec3 p, vec3 n, float footprint, vec4 own) {
    int side = int(vpl_params.interleave);
    if (side <= 1) return own; // uniform: the whole dispatch takes the same branch
    uint me = local.y * INTERLEAVE_TILE + local.x;
    interleave_share[me] = vec4(own.rgb, computed ? 1.0 : 0.0);
    interleave_position[me] = vec4(p, 0.0);
    interleave_normal[me] = vec4(n, 0.0);
    barrier();
    if (!is_new) return own;
    // Offsets -h..h, h = N / 2: every slot once for odd N; for even N the two ends share a slot
    // and take half weight each. Either way the window is centred on the pixel, so a linear
    // variation of the light across it cancels; at the tile's edges offsets outside are left
    // out (fewer shares there, and only there a half-pixel shift).
    int h = side / 2;
    bool even = (side & 1) == 0;
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int dy = -h; dy <= h; ++dy) {
        for (int dx = -h; dx <= h; ++dx) {
            ivec2 q = ivec2(local) + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(INTERLEAVE_TILE)))) continue;
            uint k = uint(q.y) * INTERLEAVE_TILE + uint(q.x);
            vec4 e = interleave_share[k];
            if (e.a == 0.0) continue;
            if (!same_surface(p, n, interleave_position[k].xyz, interleave_normal[k].xyz, footprint)) continue;
            float w = (even && abs(dx) == h ? 0.5 : 1.0) * (even && abs(dy) == h ? 0.5 : 1.0);
            sum += w * e.rgb;
            weight_sum += w;
        }
    }
    // The pixel's own share has weight 1 and is always accepted: weight_sum >= 1.
    vec3 x = sum / max(weight_sum, 1.0);
    float l = dot(x, LUMA);
    return vec4(x, l * l);
}

#endif // INTERLEAVE_GLSL
