// The visible side of two-sided surfaces, for the raster passes' fragment shaders.
#ifndef TWO_SIDED_GLSL
#define TWO_SIDED_GLSL

// Two-sided surfaces (OBJ winding is unreliable): the interpolated normal `n` of a fragment
// at `position`, flipped when it points to the other side of its triangle than `viewer` (the
// eye for the G-buffer, the light for the RSM). The side is decided per triangle, by the
// geometric normal from the position's screen derivatives: testing `n` itself against the
// viewer flipped smooth normals that turn away near a silhouette, so a surface point's normal
// changed with the view. A degenerate triangle (zero derivatives) falls back to that test.
// `visible_side` is for fragment shaders (dFdx); a compute pass that knows the triangle
// defines TWO_SIDED_NO_DERIVATIVES and calls `visible_side_of` with its plane's normal. The
// CPU reference decides alike (`Surface::facing`).
// `ng` is the triangle's geometric normal, either orientation (the product with the side of
// the viewer takes its sign out).
vec3 visible_side_of(vec3 n, vec3 ng, vec3 position, vec3 viewer) {
    vec3 to_viewer = viewer - position;
    float side = dot(ng, ng) > 0.0 ? dot(n, ng) * sign(dot(ng, to_viewer)) : dot(n, to_viewer);
    return side < 0.0 ? -n : n;
}

#ifndef TWO_SIDED_NO_DERIVATIVES
vec3 visible_side(vec3 n, vec3 position, vec3 viewer) {
    return visible_side_of(n, cross(dFdx(position), dFdy(position)), position, viewer);
}
#endif

#endif // TWO_SIDED_GLSL
