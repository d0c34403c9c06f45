#version 450 core
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 model;
void main() {
    gl_Position = frame.light_view_projection * model * vec4(position, 1.0);
}
