// Requires `history` (rgba16f storage image) declared by the including shader.
#ifndef INDIRECT_MERGE_GLSL
#define INDIRECT_MERGE_GLSL

#include "temporal.glsl"

// Merge into the history at `pixel` (rgb value, a = estimates).
void merge(ivec2 pixel, vec4 h, vec3 fresh, bool refresh) {
    vec4 result = refresh ? vec4(fresh, float(frame.rotation_limit))
                          : vec4(accumulate3(h.rgb, fresh, h.a), h.a + 1.0);
    // fp16 history: clamp to its range so an extreme VPL cannot store infinity.
    imageStore(history, pixel, vec4(clamp(result.rgb, vec3(0.0), vec3(65000.0)), result.a));
}

#endif // INDIRECT_MERGE_GLSL
