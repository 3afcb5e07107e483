// Constants and helpers every shader may use; no bindings.
#ifndef COMMON_GLSL
#define COMMON_GLSL

const float PI = 3.14159265358979;
const float TWO_PI = 6.28318530718;
const float HALF_PI = 1.57079632679490;

// Normalise with a fallback: |v|^2 below 1e-20 means a degenerate direction (interpolated
// normals and light vectors are O(1) or scene-scale, never legitimately that small).
vec3 safe_normalize(vec3 v, vec3 fallback) {
    float len2 = dot(v, v);
    return len2 > 1e-20 ? v * inversesqrt(len2) : fallback;
}

// Texel holding the continuous image position x (in texels) of an image of `size` texels:
// floor(x) after clamping x to [-1, size], so a position off the image (even infinite, from a
// tiny clip w) stays off it, one texel out, and the float-to-int conversion is defined (GLSL
// leaves it undefined outside int's range). NaN compares false and maps to -1.
ivec2 texel_of(vec2 x, vec2 size) {
    vec2 lo = mix(vec2(-1.0), x, greaterThanEqual(x, vec2(-1.0)));
    return ivec2(floor(min(lo, size)));
}

// The largest finite float: |x| below it is finite, and NaN compares false, so these remove
// what `clamp` (GLSL.std.450 FClamp) passes through.
const float FLOAT_MAX = 3.40282347e38;

bool all_finite(vec3 x) {
    return all(lessThan(abs(x), vec3(FLOAT_MAX)));
}

// x where a component is finite, 0 where it is NaN or infinite.
vec3 finite_or_zero(vec3 x) {
    return mix(vec3(0.0), x, lessThan(abs(x), vec3(FLOAT_MAX)));
}

// Rec. 709 luminance weights of linear RGB.
const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);

#endif // COMMON_GLSL
