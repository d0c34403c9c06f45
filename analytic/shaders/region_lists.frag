#version 450 core
// Writes one crossing of a region surface into its pixel's list (region_lists.glsl): the distance
// along the eye ray, + for a front face (entering), - for a back face (leaving). No colour. The
// distance comes from the triangle's corners, not from the interpolated position, which a
// triangle degenerate in float gets wrong (face_distance.glsl).
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"
#include "beamtree/shaders/region_lists.glsl"
#include "analytic/shaders/face_distance.glsl"
layout(location = SL_REGION_LISTS_SURFACE) uniform int surface;  // 0 lit, 1 uncertain
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int slot = region_slot(pixel, surface);
    uint i = atomicAdd(region_counts[slot], 1u);
    if (i < uint(REGION_LIST_SIZE)) {
        vec3 origin = frame.camera_position.xyz;
        float t = max(face_distance(origin, eye_ray_direction(gl_FragCoord.xy), gl_PrimitiveID),
                      1e-30);
        region_crossings[slot * REGION_LIST_SIZE + int(i)] = gl_FrontFacing ? t : -t;
    }
}
