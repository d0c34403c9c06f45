#version 450 core
#include "gl/shaders/object_uniforms.h"
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = SL_OBJECT_MODEL) uniform mat4 model;
layout(location = SL_OBJECT_NORMAL_MATRIX) uniform mat4 normal_matrix;  // inverse transpose of model
out vec3 world_position;
out vec3 world_normal;
void main() {
    vec4 p = model * vec4(position, 1.0);
    world_position = p.xyz;
    world_normal = mat3(normal_matrix) * normal;
    gl_Position = frame.view_projection * p;
}
