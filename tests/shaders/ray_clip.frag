#version 450 core
// Test pattern for tests/sampling_march_test.cpp: pixel (x, y) clips the camera ray through its centre,
// with trace_end = 1 + 24 x / width, to the light's pyramid (sampling/shaders/ray_clip.glsl),
// whose outward planes come from the light's matrix (Gribb & Hartmann): (start, end, case).
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"
#include "sampling/shaders/ray_clip.glsl"
layout(location = 0) out vec4 result;
void main() {
    mat4 m = transpose(frame.light_view_projection);  // rows of the matrix as columns
    vec4 planes[6] = vec4[6](m[0] - m[3], -m[0] - m[3], m[1] - m[3], -m[1] - m[3],
                             m[2] - m[3], -m[2] - m[3]);
    for (int i = 0; i < 6; ++i) planes[i] /= length(planes[i].xyz);
    float trace_end = 1.0 + 24.0 * gl_FragCoord.x / frame.display.y;
    result = vec4(clip_trace(frame.camera_position.xyz, eye_ray_direction(gl_FragCoord.xy),
                             trace_end, planes), 1.0);
}
