#version 450 core
// Test pattern for the near-light GLSL test (tests/analytic_region_pass_test.cpp): pixel (x, y)
// integrates ray y * width + x of the buffer, E(z0, z1) = G(z1) - G(z0), as the region pass does.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
struct PatternRay {
    vec4 origin_z0;     // xyz origin, w z0
    vec4 direction_z1;  // xyz unit direction, w z1
};
layout(std430, binding = 0) readonly buffer PatternRays { PatternRay rays[]; };
layout(location = 0) out vec4 result;
void main() {
    int index = int(gl_FragCoord.y) * int(frame.display.y) + int(gl_FragCoord.x);
    if (index >= rays.length()) {
        result = vec4(0.0);
        return;
    }
    vec3 origin = rays[index].origin_z0.xyz, direction = rays[index].direction_z1.xyz;
    LightSpans spans = light_spans(origin, direction);
    result = vec4(in_scattering_integral(origin, direction, spans, rays[index].direction_z1.w) -
                  in_scattering_integral(origin, direction, spans, rays[index].origin_z0.w), 1.0);
}
