#version 450 core
// Writes one crossing of a region surface into its pixel's list (region_lists.glsl): the distance
// along the eye ray, + for a front face (entering), - for a back face (leaving). No colour.
#include "gl/shaders/frame_uniforms.h"
#include "beamtree/shaders/region_lists.glsl"
layout(location = 0) uniform int surface;  // 0 lit, 1 uncertain
in vec3 world_position;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int slot = region_slot(pixel, surface);
    uint i = atomicAdd(region_counts[slot], 1u);
    if (i < uint(REGION_LIST_SIZE)) {
        float t = max(length(world_position - frame.camera_position.xyz), 1e-30);
        region_crossings[slot * REGION_LIST_SIZE + int(i)] = gl_FrontFacing ? t : -t;
    }
}
