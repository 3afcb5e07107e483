#version 460
// Probe, not a frame pass: the numerical audit of one image (`ssgi stress`, tests). Counts NaN,
// infinite and negative channel values and keeps each channel's largest finite magnitude, as a
// GPU reduction (shared memory per workgroup, one set of global atomics per workgroup). The
// renderer records it on request after a frame (src/renderer/audit.rs).
#extension GL_EXT_samplerless_texture_functions : require

layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform ImageStats {
    uvec2 size;
    // Channels of the format (1..4); the rest read as 0 or 1 and are not counted.
    uint channels;
    // Bit c set: channel c may hold negative values (positions, normals, signed flags).
    uint signed_mask;
} params;

layout(set = 0, binding = 0) uniform texture2D source;

layout(set = 0, binding = 1, std430) buffer Stats {
    uint nan_count;
    uint inf_count;
    uint negative_count;
    uint texels;
    // Largest finite |value| per channel as float bits: for non-negative floats the bit
    // pattern orders like the value, so atomicMax on the bits is a max on the values.
    uint max_bits[4];
} stats;

shared uint s_nan;
shared uint s_inf;
shared uint s_negative;
shared uint s_texels;
shared uint s_max[4];

void main() {
    uint local = gl_LocalInvocationIndex;
    if (local == 0u) {
        s_nan = 0u;
        s_inf = 0u;
        s_negative = 0u;
        s_texels = 0u;
        for (int c = 0; c < 4; ++c) s_max[c] = 0u;
    }
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(uvec2(pixel), params.size))) {
        vec4 v = texelFetch(source, pixel, 0);
        uint nan_here = 0u;
        uint inf_here = 0u;
        uint negative_here = 0u;
        for (uint c = 0u; c < params.channels; ++c) {
            float x = v[c];
            if (isnan(x)) {
                nan_here += 1u;
            } else if (isinf(x)) {
                inf_here += 1u;
            } else {
                if (x < 0.0 && (params.signed_mask & (1u << c)) == 0u) negative_here += 1u;
                atomicMax(s_max[c], floatBitsToUint(abs(x)));
            }
        }
        if (nan_here > 0u) atomicAdd(s_nan, nan_here);
        if (inf_here > 0u) atomicAdd(s_inf, inf_here);
        if (negative_here > 0u) atomicAdd(s_negative, negative_here);
        atomicAdd(s_texels, 1u);
    }
    barrier();
    if (local == 0u) {
        if (s_nan > 0u) atomicAdd(stats.nan_count, s_nan);
        if (s_inf > 0u) atomicAdd(stats.inf_count, s_inf);
        if (s_negative > 0u) atomicAdd(stats.negative_count, s_negative);
        atomicAdd(stats.texels, s_texels);
        for (int c = 0; c < 4; ++c) {
            if (s_max[c] > 0u) atomicMax(stats.max_bits[c], s_max[c]);
        }
    }
}
