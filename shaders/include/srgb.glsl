// The sRGB transfer function (IEC 61966-2-1), linear [0, 1] -> encoded.
#ifndef SRGB_GLSL
#define SRGB_GLSL

vec3 srgb_encode(vec3 linear) {
    vec3 lo = linear * 12.92;
    vec3 hi = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(linear, vec3(0.0031308)));
}

#endif
