#version 450 core
// The region lists of the walk route (analytic/region_lists.h): each pixel's eye ray walks the
// beam tree from the eye to its first surface (beamtree/shaders/walk.glsl) and writes where it
// enters (+t) and leaves (-t) the lit and the uncertain regions, the list the meshes' crossings
// give (region_lists.frag) as far as the readers ask: they read no further than the surface. A
// ray inside a region at the eye enters it at t = 1e-30. A pixel whose ray crosses none of the
// surfaces in `mark_surfaces` (bit 0 lit, bit 1 uncertain) is discarded, so that the stencil
// marks only the others. No colour.
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"
#include "beamtree/shaders/classify.glsl"
#include "beamtree/shaders/walk.glsl"
#include "beamtree/shaders/region_lists.glsl"

layout(binding = SL_ANALYTIC_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(location = SL_REGION_LISTS_MARK_SURFACES) uniform int mark_surfaces;

ivec2 pixel = ivec2(0);
// Per surface (x lit, y uncertain): the crossings written, and whether the walk is inside.
ivec2 counts = ivec2(0);
bvec2 inside = bvec2(false);

void cross_surface(int surface, int i, float signed_t) {
    if (i < REGION_LIST_SIZE) {
        region_crossings[region_slot(pixel, surface) * REGION_LIST_SIZE + i] = signed_t;
    }
}

void walk_piece(int region, float begin, float end) {
    bvec2 now = bvec2(region == REGION_LIT, region == REGION_UNCERTAIN);
    if (now.x != inside.x) cross_surface(0, counts.x++, now.x ? max(begin, 1e-30) : -begin);
    if (now.y != inside.y) cross_surface(1, counts.y++, now.y ? max(begin, 1e-30) : -begin);
    inside = now;
}

void main() {
    pixel = ivec2(gl_FragCoord.xy);
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(gl_FragCoord.xy);
    float end = eye_ray_end(surface_depth, gl_FragCoord.xy);
    if (end > 0.0) tree_walk(origin, direction, 0.0, end);
    if (inside.x) cross_surface(0, counts.x++, -end);
    if (inside.y) cross_surface(1, counts.y++, -end);
    region_counts[region_slot(pixel, 0)] = uint(counts.x);
    region_counts[region_slot(pixel, 1)] = uint(counts.y);
    bool marked = ((mark_surfaces & 1) != 0 && counts.x > 0) ||
                  ((mark_surfaces & 2) != 0 && counts.y > 0);
    if (!marked) discard;
}
