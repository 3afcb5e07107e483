// Ray queries against the scene's triangles on the GPU (issue 64): a binary BVH (obvhs's BVH2,
// flattened by src/scene/flat_bvh.rs) walked with a short stack, closest hit and any hit
// within [t_min, t_max]. The triangle test is the one the CPU reference uses (obvhs's
// Moller-Trumbore variant, src/scene/accel.rs), so the two tracers agree hit for hit.
//
// The header declares its two buffers itself, at set BVH_SET, bindings BVH_BINDING (nodes)
// and BVH_BINDING + 1 (triangles in leaf order): the includer defines both numbers first.
#ifndef BVH_GLSL
#define BVH_GLSL

#if !defined(BVH_SET) || !defined(BVH_BINDING)
#error "define BVH_SET and BVH_BINDING before including bvh.glsl"
#endif

// A node: its box, and either two children (count 0: nodes[first] and nodes[first + 1]) or a
// leaf's `count` triangles from triangles[first].
struct BvhNode {
    vec3 lo;
    uint count;
    vec3 hi;
    uint first;
};

// A triangle's corners; v0.w holds the mesh's index of the triangle (as bits).
struct BvhTriangle {
    vec4 v0;
    vec4 v1;
    vec4 v2;
};

layout(set = BVH_SET, binding = BVH_BINDING, std430) readonly buffer BvhNodes {
    BvhNode bvh_nodes[];
};
layout(set = BVH_SET, binding = BVH_BINDING + 1, std430) readonly buffer BvhTriangles {
    BvhTriangle bvh_triangles[];
};

// Most nodes on the stack: a walk holds at most the tree's depth + 1, and flat_bvh.rs refuses
// a tree deeper than BVH_STACK - 3 (BVH_MAX_DEPTH there).
const uint BVH_STACK = 64u;
const uint BVH_NONE = 0xffffffffu;

struct BvhHit {
    float t;
    uint triangle; // the mesh's triangle index; BVH_NONE: no hit
};

// 1 / d per axis, a component below 1e-30 replaced by 1e-30: the slab test then meets finite
// products (no 0 * inf NaN) for any box within 1e8 of the origin, and the ray, parallel to
// that slab, enters it only where it starts inside (the sign does not matter then).
vec3 bvh_inverse(vec3 d) {
    return 1.0 / mix(d, vec3(1e-30), lessThan(abs(d), vec3(1e-30)));
}

// The entry distance of the ray into node i's box within [t_min, t_max], or -1 if it misses.
// (Members are read one by one: glslang copies a whole buffer struct with OpCopyLogical, which
// naga's reflection cannot read.)
float bvh_enter(uint i, vec3 o, vec3 inv_d, float t_min, float t_max) {
    vec3 a = (bvh_nodes[i].lo - o) * inv_d;
    vec3 b = (bvh_nodes[i].hi - o) * inv_d;
    vec3 near = min(a, b);
    vec3 far = max(a, b);
    float enter = max(max(near.x, near.y), max(near.z, t_min));
    float leave = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= leave ? enter : -1.0;
}

// obvhs's Moller-Trumbore variant: t in [t_min, t_max], or -1. A barycentric of -0.0 counts as
// outside, as there (the sign bits are tested).
float bvh_triangle(uint i, vec3 o, vec3 d, float t_min, float t_max) {
    vec3 v0 = bvh_triangles[i].v0.xyz;
    vec3 e1 = v0 - bvh_triangles[i].v1.xyz;
    vec3 e2 = bvh_triangles[i].v2.xyz - v0;
    vec3 n = cross(e1, e2);
    vec3 c = v0 - o;
    vec3 r = cross(d, c);
    float inv_det = 1.0 / dot(n, d);
    float u = dot(r, e2) * inv_det;
    float v = dot(r, e1) * inv_det;
    float w = 1.0 - u - v;
    uint signs = floatBitsToUint(u) | floatBitsToUint(v) | floatBitsToUint(w);
    if (inv_det == 0.0 || (signs & 0x80000000u) != 0u) return -1.0;
    float t = dot(n, c) * inv_det;
    return t >= t_min && t <= t_max ? t : -1.0;
}

// The closest triangle along d (unit or not: t is in units of d) from o with t in
// [t_min, t_max], ignoring the mesh's triangle `skip` (BVH_NONE: none); with `first_hit` any
// triangle in range ends the walk (shadow and visibility rays), not only the closest.
BvhHit bvh_walk(vec3 o, vec3 d, float t_min, float t_max, uint skip, bool first_hit) {
    BvhHit hit = BvhHit(t_max, BVH_NONE);
    vec3 inv_d = bvh_inverse(d);
    uint stack[BVH_STACK];
    stack[0] = 0u;
    uint depth = 1u;
    // A full stack ends the walk (a tree deeper than flat_bvh.rs allows: cannot happen). In
    // the loop's condition, not as a `break` beside the loop's `continue`s: llvmpipe (Mesa
    // 22.3) compiled that form into a walk that stopped early (tests/gpu_bvh.rs).
    while (depth > 0u && depth < BVH_STACK - 1u) {
        depth -= 1u;
        uint node = stack[depth];
        if (bvh_enter(node, o, inv_d, t_min, hit.t) < 0.0) continue;
        uint count = bvh_nodes[node].count;
        uint first = bvh_nodes[node].first;
        if (count == 0u) {
            // The nearer child last, so it is taken first and shortens the search.
            float a = bvh_enter(first, o, inv_d, t_min, hit.t);
            float b = bvh_enter(first + 1u, o, inv_d, t_min, hit.t);
            bool a_first = a >= 0.0 && (b < 0.0 || a <= b);
            stack[depth] = a_first ? first + 1u : first;
            stack[depth + 1u] = a_first ? first : first + 1u;
            depth += 2u;
            continue;
        }
        for (uint i = first; i < first + count; ++i) {
            uint id = floatBitsToUint(bvh_triangles[i].v0.w);
            if (id == skip) continue;
            float t = bvh_triangle(i, o, d, t_min, hit.t);
            if (t >= 0.0 && (hit.triangle == BVH_NONE || t < hit.t)) hit = BvhHit(t, id);
        }
        if (first_hit && hit.triangle != BVH_NONE) return hit;
    }
    return hit;
}

BvhHit bvh_closest(vec3 o, vec3 d, float t_min, float t_max, uint skip) {
    return bvh_walk(o, d, t_min, t_max, skip, false);
}

// Whether any triangle but `skip` lies along d from o with t in [t_min, t_max].
bool bvh_any(vec3 o, vec3 d, float t_min, float t_max, uint skip) {
    return bvh_walk(o, d, t_min, t_max, skip, true).triangle != BVH_NONE;
}

#endif // BVH_GLSL
