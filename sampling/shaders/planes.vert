#version 450 core
// Sampling-plane pieces in world space, each vertex carrying its plane's eye depth.
#include "sampling/shaders/planes_interface.h"
#include "gl/shaders/frame_uniforms.h"
layout(location = SL_PLANES_POSITION_ATTRIBUTE) in vec3 position;
layout(location = SL_PLANES_DEPTH_ATTRIBUTE) in float depth;
flat out float slice_depth;
void main() {
    slice_depth = depth;
    gl_Position = frame.view_projection * vec4(position, 1.0);
}
