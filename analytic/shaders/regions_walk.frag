#version 450 core
// Volume-based integration over the lit regions without their meshes (the walk route,
// docs/design.md §14): the walk of each eye ray through the beam tree, from the eye to its first
// surface, left the pixel's lit crossings in the region lists this frame
// (analytic/shaders/region_lists_walk.frag), and each lit interval [z0, z1] adds G(z1) - G(z0),
// the same antiderivative at the same ends as the mesh route's back and front faces
// (regions.frag). Where a list overflowed, the pass walks the tree itself
// (beamtree/shaders/walk.glsl, whose pieces of one region are already merged). No eye winding
// pass is needed: a ray that starts inside a lit region has an interval from z = 0.
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "gl/shaders/view.glsl"
#include "beamtree/shaders/classify.glsl"
#include "beamtree/shaders/walk.glsl"
#include "beamtree/shaders/region_lists.glsl"

layout(binding = SL_ANALYTIC_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(location = 0) out vec4 in_scattered;

vec3 ray_origin = vec3(0.0), ray_direction = vec3(0.0);
LightSpans spans = LightSpans(vec2(0.0), vec2(0.0));
vec3 sum = vec3(0.0);

void walk_piece(int region, float begin, float end) {
    if (region == REGION_LIT) {
        sum += in_scattering_integral(ray_origin, ray_direction, spans, end) -
               in_scattering_integral(ray_origin, ray_direction, spans, begin);
    }
}

void main() {
    ray_origin = frame.camera_position.xyz;
    ray_direction = eye_ray_direction(gl_FragCoord.xy);
    float end = eye_ray_end(surface_depth, gl_FragCoord.xy);
    if (!(end > 0.0)) discard;
    spans = light_spans(ray_origin, ray_direction);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int count = region_crossing_count(pixel, 0);
    if (count >= 0) {
        // The walk wrote them in order: + where a lit interval begins, - where it ends.
        for (int i = 0; i + 1 < count; i += 2) {
            walk_piece(REGION_LIT, region_crossing(pixel, 0, i), -region_crossing(pixel, 0, i + 1));
        }
    } else {
        tree_walk(ray_origin, ray_direction, 0.0, end);
    }
    in_scattered = vec4(sum, 0.0);
}
