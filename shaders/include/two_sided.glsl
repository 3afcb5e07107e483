// The visible side of two-sided surfaces, for the raster passes' fragment shaders.
#ifndef TWO_SIDED_GLSL
#define TWO_SIDED_GLSL

// Two-sided surfaces (OBJ winding is unreliable): the interpolated normal `n` of a fragment
// at `position`, flipped when it points to the other side of its triangle than `viewer` (the
// eye for the G-buffer, the light for the RSM). The side is decided per triangle, by the
// geometric normal from the position's screen derivatives: testing `n` itself against the
// viewer flipped smooth normals that turn away near a silhouette, so a surface point's normal
// changed with the view. A degenerate triangle (zero derivatives) falls back to that test.
// Fragment shaders only (dFdx). The CPU reference decides alike (`Surface::facing`).
vec3 visible_side(vec3 n, vec3 position, vec3 viewer) {
    vec3 to_viewer = viewer - position;
    vec3 ng = cross(dFdx(position), dFdy(position));
    float side = dot(ng, ng) > 0.0 ? dot(n, ng) * sign(dot(ng, to_viewer)) : dot(n, to_viewer);
    return side < 0.0 ? -n : n;
}

#endif // TWO_SIDED_GLSL
