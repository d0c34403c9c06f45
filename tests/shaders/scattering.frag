#version 450 core
// Test pattern for tests/sampling_planes_test.cpp: pixel (x, y) takes the camera ray through its centre
// and writes e(t), t = 1 + 24 x / width (gl/shaders/scattering.glsl).
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/view.glsl"
layout(location = 0) out vec4 result;
void main() {
    float t = 1.0 + 24.0 * gl_FragCoord.x / frame.display.y;
    result = vec4(scattering_density(frame.camera_position.xyz, eye_ray_direction(gl_FragCoord.xy), t), 1.0);
}
