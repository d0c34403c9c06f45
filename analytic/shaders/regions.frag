#version 450 core
// Volume-based integration over the lit regions (Nilsson §3.2.2): each back face adds G(z), each
// front face subtracts it, into a float target with additive blending. z is clamped to the first
// surface (or the far plane): a region's two faces behind it both give G(surface) and cancel, a
// front face before it and a back face behind it give the part in front. No tolerance decides
// whether a face lying on a surface (lit regions end on them) is in front: a grazing view made
// such decisions differ between rasterizers and dropped one face of a pair. With SL_FACE_CORNERS
// (the region meshes, analytic/region_faces.h) a face's z is taken from its triangle's corners,
// not from the interpolated position, which a triangle degenerate in float gets wrong
// (face_distance.glsl); lightvolume's grid, made on the GPU, has no corners buffer and
// interpolates.
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "gl/shaders/view.glsl"
#ifdef SL_FACE_CORNERS
#include "analytic/shaders/face_distance.glsl"
#endif

layout(binding = SL_ANALYTIC_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
in vec3 world_position;
layout(location = 0) out vec4 in_scattered;

void main() {
    vec3 origin = frame.camera_position.xyz;
    // Every face of a pixel on the pixel's own eye ray, so that G depends on z alone and the
    // faces of a pair hidden behind a surface cancel exactly.
    vec3 direction = eye_ray_direction(gl_FragCoord.xy);
#ifdef SL_FACE_CORNERS
    float t = face_distance(origin, direction, gl_PrimitiveID);
#else
    float t = length(world_position - origin);
#endif
    float z = min(t, eye_ray_end(surface_depth, gl_FragCoord.xy));
    // The ray's cone interval (and inner cone, for a smooth edge): any z beyond the surface it
    // hits is clamped anyway.
    LightSpans spans = light_spans(origin, direction);
    vec3 g = in_scattering_integral(origin, direction, spans, z);
    in_scattered = vec4(gl_FrontFacing ? -g : g, 0.0);
}
