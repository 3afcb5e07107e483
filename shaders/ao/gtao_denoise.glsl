// GTAO's edge-aware 5x5 denoise weights, shared by the denoise without the cache
// (gtao_denoise.comp) and the per-pattern denoise under camera motion (gtao_moving.comp):
// screen weights 1 2 2 2 1 along each axis, times the tap's normal agreement
// (max(0, n . n_q)^16) and its distance from the centre's tangent plane in pixel footprints (a
// Gaussian of sigma 2), the joint bilateral filter's edge terms (shaders/jbf). The screen
// weights give each of the 16 slice rotations of a 4x4 tile (gtao.glsl's Bayer ranks) the same
// total weight, the two end taps of a row sharing one rotation, so on a plane the filter
// averages every slice direction; the thesis's 5x5 Gaussian weighs them 1 to 36 and blurs
// across depth edges. Needs frame.glsl.
#ifndef GTAO_DENOISE_GLSL
#define GTAO_DENOISE_GLSL

const float GTAO_DENOISE_W[5] = float[5](1.0, 2.0, 2.0, 2.0, 1.0);
const float GTAO_DENOISE_NORMAL_POWER = 16.0;
const float GTAO_DENOISE_PLANE_SIGMA = 2.0; // pixel footprints

// 1 / (sigma x the pixel footprint) at the centre's point p.
float gtao_denoise_inv_plane(vec3 p) {
    float footprint = 2.0 * distance(p, frame.camera_pos) * frame.tan_half_fov / float(frame.size.y);
    // A footprint of 0 (a surface at the eye) would divide by 0: 1e-30 is below any scene's.
    return 1.0 / max(GTAO_DENOISE_PLANE_SIGMA * footprint, 1e-30);
}

// Weight of the tap at `offset` (each component in -2..2), point q and normal n_q, for the
// centre's point p, normal n and gtao_denoise_inv_plane(p). The centre weighs 4.
float gtao_denoise_weight(ivec2 offset, vec3 p, vec3 n, float inv_plane, vec3 q, vec3 n_q) {
    float plane = dot(n, q - p) * inv_plane;
    return GTAO_DENOISE_W[offset.x + 2] * GTAO_DENOISE_W[offset.y + 2] * exp(-plane * plane) *
           pow(max(dot(n, n_q), 0.0), GTAO_DENOISE_NORMAL_POWER);
}

#endif // GTAO_DENOISE_GLSL
