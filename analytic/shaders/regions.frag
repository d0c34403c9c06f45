#version 450 core
// Volume-based integration over the lit regions (Nilsson §3.2.2): each back face adds G(z), each
// front face subtracts it, into a float target with additive blending. z is clamped to the first
// surface: a region's two faces behind it both give G(surface) and cancel, a front face before it
// and a back face behind it give the part in front. No tolerance decides whether a face lying on a
// surface (lit regions end on them) is in front: a grazing view made such decisions differ
// between rasterizers and dropped one face of a pair.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "gl/shaders/view.glsl"

layout(binding = 0) uniform sampler2D surface_depth;
in vec3 world_position;
layout(location = 0) out vec4 in_scattered;

void main() {
    vec3 origin = frame.camera_position.xyz;
    // Every face of a pixel on the pixel's own eye ray, so that G depends on z alone and the
    // faces of a pair hidden behind a surface cancel exactly.
    vec3 direction = eye_ray_direction(gl_FragCoord.xy);
    float z = min(length(world_position - origin), surface_distance(surface_depth, gl_FragCoord.xy));
    // The ray's cone interval (and inner cone, for a smooth edge): any z beyond the surface it
    // hits is clamped anyway.
    LightSpans spans = light_spans(origin, direction);
    vec3 g = in_scattering_integral(origin, direction, spans, z);
    in_scattered = vec4(gl_FrontFacing ? -g : g, 0.0);
}
