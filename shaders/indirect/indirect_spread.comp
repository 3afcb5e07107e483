#version 460
// The indirect light's few-pixel passes with each estimate spread over the lanes of a
// workgroup and summed in shared memory: a GPU charges a workgroup whose lanes idle nearly as
// much as a full one, and one lane looping over every VPL costs that loop's latency however
// few pixels it serves (0.36 ms for 3 fix-up pixels on an H200 when each was one lane).
// `gather`:  the low-resolution samples indirect_classify.comp listed, each with every VPL
//            of this frame's pattern on --vpl-lanes lanes, into the low-resolution image.
// `fixup`:   the pixels the upsampling discarded (the list after the blocks in counters.data),
//            each with every VPL of this frame's pattern, merged into the history.
// `refresh`: every (pixel, pattern) pair of the refresh tile, one estimate each, into
//            `partials` (pixel-major: pixel i's patterns at i * rotation_limit ...).
//            At half resolution (`refresh_lowres`): every (low-resolution sample, pattern)
//            pair of the samples the tile's pixels are upsampled from (refresh_samples), each
//            gathered as `gather` gathers it, so the resolve can hold the estimator the
//            accumulation converges to there, at about a third of the tile's pixel count.
// `resolve`: per refresh-tile pixel, the mean of its patterns blended into the history along
//            the tile's feather ramp; it runs after `refresh`, and the other passes leave
//            refresh pixels alone.
// A workgroup takes SPREAD_LANES / L estimates at once (L = the VPL parameters' spread_lanes:
// up to 64 for the few-pixel passes, gather_lanes: up to --vpl-lanes for the gather) and strides over its list by the
// dispatch's width when the list is longer than the dispatch.
// @permutation gather: GATHER
// @permutation fixup: FIXUP
// @permutation refresh: REFRESH
// @permutation refresh_lowres: REFRESH LOWRES
// @permutation resolve: RESOLVE
// @permutation resolve_lowres: RESOLVE LOWRES
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "frame.glsl"
#include "temporal.glsl"
#define COUNTERS_BINDING 5
#include "counters.glsl"
#include "effect.glsl"
#include "shared_constants.glsl"

layout(local_size_x = SPREAD_LANES) in;

#ifdef GATHER
layout(set = 1, binding = 6, rgba32f) uniform writeonly image2D lowres;
layout(set = 1, binding = 11, std430) buffer Claims { uint claims[]; };
#else
layout(set = 1, binding = 6, INDIRECT_HISTORY_FORMAT) uniform image2D history;
layout(set = 1, binding = 7, STATE_FORMAT) uniform readonly uimage2D state_in;
layout(set = 1, binding = 8, MOMENTS_FORMAT) uniform image2D moments;
#endif
#if defined(REFRESH) || defined(RESOLVE)
layout(set = 1, binding = 9, std430) buffer Partials { vec4 partials[]; };
#endif

#include "indirect_common.glsl"
#ifndef GATHER
#include "indirect_merge.glsl"
#endif

#ifdef LOWRES
// The low-resolution samples the refresh tile's pixels are upsampled from (a pixel reads the
// sample at pixel / 2 and, when odd, the next): `origin` and `count` per axis, clipped to the
// low-resolution image. Also temporal.rs `tile_evaluations`.
void refresh_samples(out ivec2 origin, out ivec2 count) {
    uvec4 r = effect.refresh_rect;
    ivec2 low_size = ivec2((frame.size + 1u) / 2u);
    origin = ivec2(r.xy) >> 1;
    ivec2 last = min((ivec2(max(r.zw, uvec2(1u))) - 1) / 2 + 1, low_size - 1);
    count = r.z > r.x && r.w > r.y ? max(last - origin + 1, ivec2(0)) : ivec2(0);
}
#endif

#ifdef GATHER
#define LANES_PER_ESTIMATE vpl_params.gather_lanes
#else
#define LANES_PER_ESTIMATE vpl_params.spread_lanes
#endif

#if defined(RESOLVE) && defined(LOWRES)
// Sample `low`'s mean over every pattern (rgb, and the mean squared luminance).
vec4 sample_mean(ivec2 low, ivec2 origin, ivec2 count) {
    uint limit = frame.rotation_limit;
    ivec2 s = low - origin;
    uint first = uint(s.y * count.x + s.x) * limit;
    vec4 total = vec4(0.0);
    for (uint j = 0u; j < limit; ++j) total += partials[first + j];
    return total / float(limit);
}

// Per refresh-tile pixel: the upsampling (indirect_upsample.comp's weights and surface tests)
// of its samples' means, which is the mean of the upsampled patterns the accumulation holds
// (the weights depend on geometry only), blended into the history. A pixel the upsampling
// discards keeps its history this frame: the fix-up's full-resolution gather accumulates it.
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= refresh_tile_pixels()) return;
    ivec2 pixel = refresh_tile_pixel(i);
    if (outside_frame(pixel) || imageLoad(state_in, pixel).r != STATE_REFRESH) return;
    ivec2 origin, count;
    refresh_samples(origin, count);
    vec3 p = texelFetch(g_position, pixel, 0).xyz;
    vec3 n = texelFetch(g_normal, pixel, 0).xyz;
    float footprint = pixel_footprint(p, 1.0);
    ivec2 base = pixel >> 1;
    vec2 w = vec2(pixel & 1) * 0.5;
    vec4 sum = vec4(0.0);
    float weight_sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 low = base + o;
        float weight = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        if (weight == 0.0 || any(greaterThanEqual(low - origin, count))) continue;
        vec4 g = texelFetch(g_position, low * 2, 0);
        if (g.w == 0.0) continue;
        if (!same_surface(p, n, g.xyz, texelFetch(g_normal, low * 2, 0).xyz, footprint)) continue;
        sum += weight * sample_mean(low, origin, count);
        weight_sum += weight;
    }
    if (weight_sum <= 0.0) return;
    merge(pixel, imageLoad(history, pixel), sum / weight_sum, true);
    atomicAdd(counters.computed_pixels, 1u);
}
#elif defined(RESOLVE)
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= refresh_tile_pixels()) return;
    ivec2 pixel = refresh_tile_pixel(i);
    if (outside_frame(pixel) || imageLoad(state_in, pixel).r != STATE_REFRESH) return;
    uint limit = frame.rotation_limit;
    vec4 total = vec4(0.0); // patterns' values (rgb) and squared luminances
    for (uint j = 0u; j < limit; ++j) total += partials[i * limit + j];
    merge(pixel, imageLoad(history, pixel), total / float(limit), true);
    atomicAdd(counters.computed_pixels, 1u);
    atomicAdd(counters.refresh_evaluations, limit);
}
#else
shared vec4 part[SPREAD_LANES];
shared uint group_active;
shared uint group_serial;
shared uint group_estimates; // estimates computed (the gather's samples, the refresh's pairs)

// The list's `item`-th estimate: its pixel (for the gather the low-resolution one), the
// full-resolution texel its surface is read at, its pattern, and whether it is computed.
bool list_item(uint item, out ivec2 pixel, out ivec2 texel, out uint pattern) {
#ifdef GATHER
    uint packed = counters.data[counters.lowres_list + item];
    pixel = ivec2(packed & 0xffffu, packed >> 16);
    texel = pixel * 2; // the classification listed only samples on geometry
    pattern = effect.pattern;
    return true;
#elif defined(FIXUP)
    uint packed = counters.data[counters.max_blocks + item];
    pixel = ivec2(packed & 0xffffu, packed >> 16);
    texel = pixel;
    pattern = effect.pattern;
    uint state = imageLoad(state_in, pixel).r;
    return state == STATE_NEW || state == STATE_ACCUMULATING;
#elif defined(LOWRES)
    uint limit = frame.rotation_limit;
    ivec2 origin, count;
    refresh_samples(origin, count);
    uint s = item / limit;
    pixel = origin + ivec2(int(s) % count.x, int(s) / count.x);
    texel = pixel * 2; // as the gather: the sample's G-buffer texel, rotated by its own pixel
    pattern = item % limit;
    return true; // background samples are skipped by the caller's geometry test
#else
    uint limit = frame.rotation_limit;
    pixel = refresh_tile_pixel(item / limit);
    texel = pixel;
    pattern = item % limit;
    return !outside_frame(pixel) && imageLoad(state_in, pixel).r == STATE_REFRESH;
#endif
}

void main() {
    uint lanes = LANES_PER_ESTIMATE;
    uint per_group = SPREAD_LANES / lanes;
    uint t = gl_LocalInvocationIndex;
    uint lane = t % lanes;
    // This lane's evaluations per estimate: VPLs lane, lane + lanes, ... of the gather.
    uint work = rsm_gather_evaluations();
    uint share = lane < work ? (work - lane + lanes - 1u) / lanes : 0u;
#ifdef GATHER
    uint items = counters.lowres_samples;
#elif defined(FIXUP)
    uint items = counters.fixup_pixels;
#elif defined(LOWRES)
    ivec2 origin, count;
    refresh_samples(origin, count);
    uint items = uint(count.x * count.y) * frame.rotation_limit;
#else
    uint items = refresh_tile_pixels() * frame.rotation_limit;
#endif
    if (t == 0u) {
        group_active = 0u;
        group_serial = 0u;
        group_estimates = 0u;
    }
    uint evaluations = 0u; // this lane's, over every round
    uint busy = 0u;        // rounds in which this lane evaluated
    uint rounds = 0u;
    // Uniform over the workgroup: `items` is one value every lane reads.
    for (uint first = gl_WorkGroupID.x * per_group; first < items;
         first += gl_NumWorkGroups.x * per_group) {
        uint item = first + t / lanes;
        ivec2 pixel = ivec2(0);
        ivec2 texel = ivec2(0);
        uint pattern = 0u;
        bool live = item < items && list_item(item, pixel, texel, pattern);
        vec3 x = vec3(0.0);
        if (live) {
            vec4 position = texelFetch(g_position, texel, 0);
            live = position.w != 0.0;
            if (live) x = indirect_part(position.xyz, texelFetch(g_normal, texel, 0).xyz, pattern, pixel, lane, lanes);
            if (live && planted_nan(texel)) x = vec3(quiet_nan());
        }
        if (live && share > 0u) {
            evaluations += share;
            busy += 1u;
        }
        rounds += 1u;
        part[t] = vec4(x, 0.0);
        barrier();
        for (uint h = lanes / 2u; h > 0u; h >>= 1u) {
            if (lane < h) part[t] += part[t + h];
            barrier();
        }
        if (lane == 0u && live) {
            vec3 e = part[t].rgb;
            float l = dot(e, LUMA);
#ifdef GATHER
            imageStore(lowres, pixel, vec4(e, l * l));
            // Released for the next frame's classification (only block borders are claimed).
            if ((pixel.x & 7) == 0 || (pixel.y & 7) == 0)
                claims[uint(pixel.y) * ((frame.size.x + 1u) / 2u) + uint(pixel.x)] = 0u;
            atomicAdd(group_estimates, 1u);
#elif defined(FIXUP)
            merge(pixel, imageLoad(history, pixel), vec4(e, l * l), false);
#else
            partials[item] = vec4(e, l * l);
            atomicAdd(group_estimates, 1u);
#endif
        }
        barrier();
    }
    if (busy > 0u) {
        atomicAdd(group_active, busy);
        atomicMax(group_serial, evaluations);
    }
    barrier();
    // Launched and live count lane-rounds: a lane that strides over the list is launched
    // once per round.
    if (t != 0u || rounds == 0u) return;
#ifdef GATHER
    if (group_estimates > 0u) atomicAdd(counters.computed_pixels, group_estimates);
    COUNT_WORK(gather, rounds * SPREAD_LANES, group_active, group_serial)
#elif defined(FIXUP)
    COUNT_WORK(fixup, rounds * SPREAD_LANES, group_active, group_serial)
#else
#ifdef LOWRES
    // At full resolution the resolve counts its pixels' patterns; here the samples' are the
    // evaluations.
    if (group_estimates > 0u) atomicAdd(counters.refresh_evaluations, group_estimates);
#endif
    COUNT_WORK(refresh, rounds * SPREAD_LANES, group_active, group_serial)
#endif
}
#endif
