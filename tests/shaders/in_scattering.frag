#version 450 core
// Test pattern for the GLSL/C++ agreement test (tests/analytic_region_pass_test.cpp): pixel (x, y) takes
// the camera ray through its centre and writes E(0, t) = G(t) - G(0), t = 1 + 24 x / width.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "analytic/shaders/in_scattering.glsl"
layout(location = 0) out vec4 result;
void main() {
    vec2 size = frame.display.yz;
    vec2 ndc = 2.0 * gl_FragCoord.xy / size - 1.0;
    vec4 far = frame.inverse_view_projection * vec4(ndc, 1.0, 1.0);
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = normalize(far.xyz / far.w - origin);
    float t = 1.0 + 24.0 * gl_FragCoord.x / size.x;
    LightSpans spans = light_spans(origin, direction);
    result = vec4(in_scattering_integral(origin, direction, spans, t) -
                  in_scattering_integral(origin, direction, spans, 0.0), 1.0);
}
