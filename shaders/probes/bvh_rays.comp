#version 460
// Probe: traces a list of rays through the BVH (shaders/include/bvh.glsl) and writes each
// one's closest hit and any-hit answer, for tests/gpu_bvh.rs to compare with the CPU tracer.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

// Ray i: origin (xyz) and t_min (w), direction (xyz) and t_max (w).
struct ProbeRay {
    vec4 origin;
    vec4 direction;
};

layout(set = 0, binding = 0, std430) readonly buffer Rays {
    ProbeRay rays[];
};
// Per ray: the closest hit's t (t_max when none), its triangle's bits (BVH_NONE when none),
// 1 when any triangle lies within [t_min, t_max] (bvh_any), 0.
layout(set = 0, binding = 1, std430) buffer Hits {
    vec4 hits[];
};

#define BVH_SET 0
#define BVH_BINDING 2
#include "bvh.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(rays.length())) return;
    vec4 origin = rays[i].origin;
    vec4 direction = rays[i].direction;
    BvhHit hit = bvh_closest(origin.xyz, direction.xyz, origin.w, direction.w, BVH_NONE);
    bool any = bvh_any(origin.xyz, direction.xyz, origin.w, direction.w, BVH_NONE);
    hits[i] = vec4(hit.t, uintBitsToFloat(hit.triangle), any ? 1.0 : 0.0, 0.0);
}
