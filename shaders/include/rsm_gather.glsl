// One-bounce indirect light from the reflective shadow map (Lin 2013 eqs 9-10, Dachsbacher &
// Stamminger 2005). Requires rsm_position, rsm_normal, rsm_flux, g_position (for the visibility
// test) to be declared by the including shader.
#ifndef RSM_GATHER_GLSL
#define RSM_GATHER_GLSL

#include "frame.glsl"
#include "patterns.glsl"
#include "spread.glsl"

// Flux Phi_q of the VPL at RSM texel `texel`, world position q: the stored albedo x I times
// the factors rsm.frag leaves out to keep fp16 values normal, the spot's cone factor and the
// texel's solid angle. On the light's image plane at unit distance a texel has area
// (2 tan(fov/2) / N)^2; seen off-axis at angle t it subtends that area times cos^3(t).
vec3 vpl_flux(vec3 q, ivec2 texel) {
    vec3 dir = safe_normalize(q - frame.light_pos, frame.light_dir);
    float cos_axis = max(dot(dir, frame.light_dir), 0.0);
    float side = 2.0 * frame.light_tan_half_fov / frame.shadow_map_size;
    float solid_angle = side * side * cos_axis * cos_axis * cos_axis;
    return texelFetch(rsm_flux, texel, 0).rgb * (spot_factor(dir) * solid_angle);
}

// Eq 9 for one VPL q at receiver p (normal n): Phi_q max(0, n.D) max(0, n_q.(-D)) / |q-p|^2.
// |q-p|^2 is floored at the squared world size of one RSM texel at q: a VPL stands for a
// texel-sized patch and the point-light law only holds beyond about its own size, so the
// singularity at q -> p is cut at a distance that scales with the light's frustum, not a fixed
// world epsilon.
vec3 vpl_contribution(vec3 p, vec3 n, ivec2 texel) {
    vec4 q = texelFetch(rsm_position, texel, 0);
    if (q.w == 0.0) return vec3(0.0);
    vec3 nq = texelFetch(rsm_normal, texel, 0).xyz;
    vec3 d = q.xyz - p;
    float d2 = dot(d, d);
    float depth = max(dot(q.xyz - frame.light_pos, frame.light_dir), 0.0);
    float texel_world = 2.0 * depth * frame.light_tan_half_fov / frame.shadow_map_size;
    if (d2 <= 0.0) return vec3(0.0);
    vec3 dir = d * inversesqrt(d2); // eq 10
    return vpl_flux(q.xyz, texel) * max(dot(n, dir), 0.0) * max(dot(nq, -dir), 0.0) / max(d2, texel_world * texel_world);
}

// One point of the screen-space visibility march: false when the point at parameter t of the
// segment p -> q lies behind the visible surface (by more than 2% of its depth). Points off
// screen or over the background give no information.
bool march_point_visible(vec3 p, vec3 q, float t) {
    vec4 cs = frame.view_proj * vec4(mix(p, q, t), 1.0);
    if (cs.w <= 0.0) return true;
    ivec2 px = texel_of((cs.xy / cs.w * 0.5 + 0.5) * vec2(frame.size), vec2(frame.size));
    if (outside_frame(px)) return true;
    vec4 g = texelFetch(g_position, px, 0);
    if (g.w == 0.0) return true;
    float zg = (frame.view_proj * vec4(g.xyz, 1.0)).w;
    return cs.w <= zg * 1.02;
}

// Screen-space visibility of q from p (Lin 2013 section 3.3.1): points on the segment at eq 8's
// log spacing in screen space, m = 8 steps, the last ones spanning the far part of the segment;
// stopping at 95% keeps q's own surface from occluding it. Written without a loop: llvmpipe
// caps the iterations of each loop per invocation, and this runs once per VPL.
bool vpl_visible(vec3 p, vec3 q) {
    vec4 cp = frame.view_proj * vec4(p, 1.0);
    vec4 cq = frame.view_proj * vec4(q, 1.0);
    if (cp.w <= 0.0 || cq.w <= 0.0) return true;
    vec2 size = vec2(frame.size);
    float len = length((cq.xy / cq.w - cp.xy / cp.w) * 0.5 * size);
    float near_px = vpl_params.march_near_px;
    if (len <= near_px) return true;
    float ratio = len / near_px;
    #define STEP(i) march_point_visible(p, q, min(near_px * pow(ratio, float(i) / 8.0) / len, 0.95))
    return STEP(1) && STEP(2) && STEP(3) && STEP(4) && STEP(5) && STEP(6) && STEP(7) && STEP(8);
    #undef STEP
}

vec3 vpl_term(vec3 p, vec3 n, ivec2 texel) {
    vec3 c = vpl_contribution(p, n, texel);
    if (vpl_params.visibility != 0u && any(greaterThan(c, vec3(0.0)))) {
        if (!vpl_visible(p, texelFetch(rsm_position, texel, 0).xyz)) return vec3(0.0);
    }
    return c;
}

// The R2 low-discrepancy sequence (Roberts 2018), point i of the unit square: fract(0.5 + i a)
// with a = (1/g, 1/g^2), g the plastic number. In 0.32 fixed point (round(a 2^32)), where the
// wrap of uint arithmetic is the fract: float(i) * a in fp32 keeps only about 1e-3 of the
// fraction at i = 16384. `shift` (0.32 fixed point) is added to the first coordinate. The top
// 24 bits convert exactly to a float below 1.
const uvec2 R2_ALPHA = uvec2(0xC13FA9A9u, 0x91E10DA6u);
// round(2^32 / phi): consecutive multiples mod 2^32 are maximally spread (per-pattern shifts).
const uint INV_GOLDEN_RATIO_FIXED = 0x9E3779B9u;
vec2 r2_point(uint i, uint shift) {
    uvec2 u = uvec2(0x80000000u + shift, 0x80000000u) + i * R2_ALPHA;
    return vec2(u >> 8u) * (1.0 / 16777216.0);
}

// The centre of the VPL density for a receiver at p: its projection into the RSM [texels].
// Any centre keeps the estimator unbiased, so points behind the light or projecting outside
// use the nearest RSM point (the centre when behind): otherwise nearly every sample would miss
// the map.
vec2 rsm_centre(vec3 p) {
    float size = frame.shadow_map_size;
    vec4 clip = frame.light_view_proj * vec4(p, 1.0);
    return clip.w > 0.0 ? clamp((clip.xy / clip.w * 0.5 + 0.5) * size, vec2(0.0), vec2(size))
                        : vec2(0.5 * size);
}

// Eq 9 over the RSM texels of share `share` of an N x N split (N = side): the texels with
// (x mod N, y mod N) = share, a sub-lattice as even in both directions as the map, times N^2,
// so that the mean over the N^2 shares is exactly the sum over every texel (also when N does
// not divide the map's side and shares differ by a row); side 1: every texel, the reference
// the sampled gather converges to. The configuration limits this to RSMs of at most 128x128 texels
// (RenderConfig::validate): llvmpipe caps loop iterations per invocation and GPU drivers reset
// devices on long dispatches.
vec3 rsm_gather_all(vec3 p, vec3 n, uvec2 share, uint side) {
    uint size = uint(frame.shadow_map_size);
    vec3 sum = vec3(0.0);
    for (uint y = share.y; y < size; y += side)
        for (uint x = share.x; x < size; x += side)
            sum += vpl_term(p, n, ivec2(x, y));
    return side == 1u ? sum : sum * float(side * side);
}

// Lane `lane` of `lanes` of the every-texel gather (side 1): texels lane, lane + lanes, ... in
// row-major order, unscaled. The lanes' sum is rsm_gather_all(p, n, uvec2(0), 1).
vec3 rsm_gather_all_part(vec3 p, vec3 n, uint lane, uint lanes) {
    uint size = uint(frame.shadow_map_size);
    vec3 sum = vec3(0.0);
    for (uint k = lane; k < size * size; k += lanes)
        sum += vpl_term(p, n, ivec2(k % size, k / size));
    return sum;
}

// VPLs drawn around p's projection into the RSM with a density that falls off as
// 1/r^2 beyond one texel (uniform inside it), each weighted by the inverse density, i.e. by its
// squared distance (Dachsbacher & Stamminger's weighting). The disc reaches the farthest RSM
// corner, so the estimator is unbiased for the sum over every texel. The VPLs are points
// [first, end) of one R2 sequence: a run of a Kronecker sequence is a shifted prefix of it,
// as even in both dimensions as the whole, so a run is an unbiased share of the first `end`
// points (every k-th point instead would lie on a few lines: a stride of the R2 lattice is a
// poor lattice). `pattern` rotates the points and shifts the radii (a new pattern each
// frame); `seed` rotates per pixel (per interleaving block).
vec3 rsm_sampled_sum(vec3 p, vec3 n, uint pattern, uint first, uint end, uint stride, float seed) {
    float size = frame.shadow_map_size;
    vec2 c = rsm_centre(p);
    vec2 far_corner = max(abs(c), abs(c - vec2(size)));
    float r0 = 1.0;
    float R = max(length(far_corner), 2.0 * r0);
    float log_ratio = log(R / r0);
    float p_inner = 1.0 / (1.0 + 2.0 * log_ratio);  // probability of the inner disc
    float density = p_inner / (PI * r0 * r0); // C in p(x) = C / max(r, r0)^2
    // Pattern j shifts the radii by frac(j / phi) and rotates by 2 pi times the base-2 radical
    // inverse of j: a 2D low-discrepancy sequence over patterns, so any prefix of them covers
    // both dimensions evenly and no rotation repeats (a fixed angle step would repeat every
    // 360 / step patterns). Patterns are small non-negative integers: the conversion is exact.
    uint j = pattern;
    float angle = TWO_PI * (float(bitfieldReverse(j) >> 8) * (1.0 / 16777216.0) + seed);
    uint shift = j * INV_GOLDEN_RATIO_FIXED;
    vec3 sum = vec3(0.0);
    for (uint i = first; i < end; i += stride) {
        vec2 u = r2_point(i, shift);
        float u1 = u.x;
        float u2 = u.y;
        float r = u1 < p_inner ? r0 * sqrt(u1 / p_inner) : r0 * exp(log_ratio * (u1 - p_inner) / (1.0 - p_inner));
        float phi = TWO_PI * u2 + angle;
        vec2 x = c + r * vec2(cos(phi), sin(phi));
        // Written so NaN fails too: the texel conversion below needs x inside the map.
        if (!(all(greaterThanEqual(x, vec2(0.0))) && all(lessThan(x, vec2(size))))) continue;
        float weight = max(r, r0) * max(r, r0) / (density * r0 * r0);
        sum += weight * vpl_term(p, n, ivec2(floor(x)));
    }
    return sum;
}

// The mean over points [first, end) of the sequence: one pattern's estimate from that run.
vec3 rsm_gather_sampled(vec3 p, vec3 n, uint pattern, uint first, uint end, float seed) {
    return rsm_sampled_sum(p, n, pattern, first, end, 1u, seed) / float(max(end - first, 1u));
}

// Pattern `pattern` at `pixel` from the pixel's share of the VPLs: every VPL with
// interleave 1. With interleave N > 1 (Keller & Heidrich 2001) the VPLs split into N^2
// shares, and the pixels of each N x N block take different ones: slot
// s = (x mod N) + N (y mod N), share (s + pattern) mod N^2. Any N x N window holds every share
// of the pattern once (interleave.glsl puts them back together for new pixels), and over N^2
// consecutive patterns every pixel takes every share, so its own accumulated shares converge
// to the whole gather.
vec3 rsm_gather(vec3 p, vec3 n, uint pattern, ivec2 pixel, uint interleave) {
    uint shares = interleave * interleave;
    uvec2 slot = uvec2(pixel) % interleave;
    uint share = (slot.x + interleave * slot.y + pattern % shares) % shares;
    uint vpls = vpl_params.count;
    if (vpls == 0u) return rsm_gather_all(p, n, uvec2(share % interleave, share / interleave), interleave);
    // Per-block rotation: interleaved gradient noise (Jimenez 2014), stable per block.
    float seed = interleaved_gradient_noise(pixel / int(interleave));
    // vpls <= 16384 and shares <= 64 (RenderConfig::validate): no overflow.
    return rsm_gather_sampled(p, n, pattern, share * vpls / shares, (share + 1u) * vpls / shares, seed);
}

// Lane `lane` of `lanes` of pattern `pattern`'s every-VPL gather at `pixel` (rsm_gather with
// interleave 1): the lanes' parts sum to it, each lane evaluating every lanes-th VPL, so a
// workgroup gathers one pixel in 1 / lanes of one thread's time.
vec3 rsm_gather_part(vec3 p, vec3 n, uint pattern, ivec2 pixel, uint lane, uint lanes) {
    uint vpls = vpl_params.count;
    if (vpls == 0u) return rsm_gather_all_part(p, n, lane, lanes);
    float seed = interleaved_gradient_noise(pixel);
    return rsm_sampled_sum(p, n, pattern, lane, vpls, lanes, seed) / float(vpls);
}

#endif // RSM_GATHER_GLSL
