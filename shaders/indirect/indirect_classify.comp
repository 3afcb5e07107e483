#version 460
// Lists the low-resolution samples the half-resolution gather computes this frame (without
// interleaving), so that indirect_spread.comp's `gather` launches lanes for those samples only
// instead of a workgroup per 16x16 block whose lanes mostly idle where few pixels accumulate.
// Over the blocks the reprojection listed, each workgroup tests the block's 8x8 samples and
// its right and bottom apron (9x9: the samples indirect_upsample.comp's bilinear taps read for
// the block's pixels). A sample is listed when it lies on geometry and a full-resolution pixel
// within one pixel of its texel is new or accumulating: exactly the taps with weight that
// such pixels read. Border samples belong to two or four blocks' 9x9 windows: the first
// workgroup to claim one (`claims`, released by the gather) lists it, so each sample is
// listed once. Each workgroup reserves its run of the list with one atomic.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "shared_constants.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "spread.glsl"

layout(local_size_x = 9, local_size_y = 9) in;

layout(set = 1, binding = 0) uniform texture2D g_position;
layout(set = 1, binding = 7, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 11, std430) buffer Claims { uint claims[]; }; // one per sample, in rows

shared uint group_count;
shared uint group_base;

// Whether a full-resolution pixel within one pixel of `full` is new or accumulating.
bool sample_needed(ivec2 full) {
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = full + ivec2(dx, dy);
            if (outside_frame(q)) continue;
            uint state = imageLoad(state_in, q).r;
            if (state == STATE_NEW || state == STATE_ACCUMULATING) return true;
        }
    }
    return false;
}

void main() {
    // Uniform over the workgroup: a group past the list returns whole, before any barrier.
    uint group = listed_group();
    if (group >= counters.listed_blocks) return;
    if (gl_LocalInvocationIndex == 0u) group_count = 0u;
    barrier();
    uint packed = counters.data[group];
    uvec2 local = gl_LocalInvocationID.xy;
    ivec2 low = ivec2(packed & 0xffffu, packed >> 16) * 8 + ivec2(local);
    ivec2 low_size = ivec2((frame.size + 1u) / 2u);
    bool listed = false;
    uint index = 0u;
    if (all(lessThan(low, low_size))) {
        ivec2 full = low * 2;
        listed = texelFetch(g_position, full, 0).w != 0.0 && sample_needed(full);
        // Samples on a block border (low % 8 == 0) are in a neighbour's window too.
        bool border = local.x == 0u || local.x == 8u || local.y == 0u || local.y == 8u;
        uint claim = uint(low.y) * uint(low_size.x) + uint(low.x);
        if (listed && border) listed = atomicExchange(claims[claim], 1u) == 0u;
    }
    if (listed) index = atomicAdd(group_count, 1u);
    barrier();
    if (gl_LocalInvocationIndex == 0u && group_count > 0u) {
        group_base = atomicAdd(counters.lowres_samples, group_count);
        // The gather's workgroups take SPREAD_LANES / L samples each; past the device's
        // maxComputeWorkGroupCount[0] they stride over the list.
        uint per_group = SPREAD_LANES / vpl_params.gather_lanes;
        uint groups = (group_base + group_count + per_group - 1u) / per_group;
        atomicMax(counters.lowres_dispatch_x, min(groups, max(frame.max_groups_x, 1u)));
    }
    barrier();
    if (listed)
        counters.data[counters.lowres_list + group_base + index] = uint(low.x) | (uint(low.y) << 16);
}
