#version 450 core
// Sampling-plane pieces in world space, each vertex carrying its plane's eye depth.
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
layout(location = 1) in float depth;
flat out float slice_depth;
void main() {
    slice_depth = depth;
    gl_Position = frame.view_projection * vec4(position, 1.0);
}
