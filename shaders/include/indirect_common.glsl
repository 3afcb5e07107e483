// Shared by the indirect-light passes: the RSM inputs and the pattern choice.
layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 1) uniform texture2D g_normal;
layout(set = 1, binding = 2) uniform texture2D rsm_position;
layout(set = 1, binding = 3) uniform texture2D rsm_normal;
layout(set = 1, binding = 4) uniform texture2D rsm_flux;

#include "rsm_gather.glsl"

// Whether full-resolution pixel `pixel` lies in this frame's refresh tile.
bool in_refresh_tile(ivec2 pixel) {
    uvec2 tile = effect.refresh_origin;
    return tile.x != 0xffffffffu && all(greaterThanEqual(uvec2(pixel), tile)) &&
           all(lessThan(uvec2(pixel), tile + effect.refresh_tile));
}

// Fresh estimate for a pixel: every pattern up to the rotation limit in the refresh tile (a
// recompute from scratch), else this frame's pattern.
vec3 fresh_gather(vec3 p, vec3 n, bool refresh, ivec2 seed_pixel) {
    return refresh ? rsm_gather(p, n, 0.0, frame.rotation_limit, seed_pixel)
                   : rsm_gather(p, n, float(effect.pattern), 1u, seed_pixel);
}

