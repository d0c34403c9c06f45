#version 450 core
// The eye inside the lit regions (analytic/region_pass.h): each eye ray starts inside, and its
// entry face lies behind the eye, so nothing subtracts G at the ray's start. This full-screen pass
// subtracts G(0) once per region about the eye (`windings`), as the missing front faces at z = 0
// would (regions.frag); the closed form's antiderivative is not 0 there.
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "gl/shaders/view.glsl"

layout(location = SL_REGIONS_EYE_WINDINGS) uniform float windings;
layout(location = 0) out vec4 in_scattered;

void main() {
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(gl_FragCoord.xy);
    LightSpans spans = light_spans(origin, direction);
    in_scattered = vec4(-windings * in_scattering_integral(origin, direction, spans, 0.0), 0.0);
}
