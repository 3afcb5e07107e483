// Per draw (push constants of the raster passes): the material's colour and where the drawn
// object stands this frame and stood last frame, as the rows of 3x4 affine object -> world
// matrices (the identity for what stands still: a moving object is drawn from its own space).
// build.rs generates the Rust struct `MaterialPush` from this block.
#ifndef MATERIAL_GLSL
#define MATERIAL_GLSL

layout(push_constant) uniform Material {
    vec4 albedo;
    vec4 model_x;      // this frame's object -> world, rows
    vec4 model_y;
    vec4 model_z;
    vec4 prev_model_x; // last frame's
    vec4 prev_model_y;
    vec4 prev_model_z;
} material;

// A point of the object in the world, this frame. With the identity rows the products by 0
// and 1 are exact: what stands still keeps its coordinates bit for bit.
vec3 place(vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec3(dot(material.model_x, h), dot(material.model_y, h), dot(material.model_z, h));
}

// The same point last frame.
vec3 place_prev(vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec3(dot(material.prev_model_x, h), dot(material.prev_model_y, h),
                dot(material.prev_model_z, h));
}

// A direction of the object (a normal: the transform is a rotation and a uniform scale, so
// the fragment stage's normalisation is all a normal needs).
vec3 place_direction(vec3 d) {
    return vec3(dot(material.model_x.xyz, d), dot(material.model_y.xyz, d),
                dot(material.model_z.xyz, d));
}

#endif
