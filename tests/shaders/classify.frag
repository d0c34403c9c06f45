#version 450 core
// Test pattern for tests/beamtree_gpu_test.cpp: pixel (x, y) classifies the world point stored
// at (x, y) of `points` with the GLSL classify, writing the region into red.
#include "gl/shaders/frame_uniforms.h"
#include "beamtree/shaders/classify.glsl"
layout(binding = 0) uniform sampler2D points;
layout(location = 0) out vec4 result;
void main() {
    vec3 p = texelFetch(points, ivec2(gl_FragCoord.xy), 0).xyz;
    result = vec4(float(classify_region(p)), 0.0, 0.0, 1.0);
}
