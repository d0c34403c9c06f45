#version 450 core
// Lit-region faces of the beam tree, in world space.
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
out vec3 world_position;
void main() {
    world_position = position;
    gl_Position = frame.view_projection * vec4(position, 1.0);
}
