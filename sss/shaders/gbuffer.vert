#version 450 core
// Positions and normals of the objects seen from a camera or a light (Rohat listing 5.2), in
// world space.

#include "gl/shaders/object_uniforms.h"
#include "sss/shaders/subsurface_interface.h"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = SL_OBJECT_MODEL) uniform mat4 model;
layout(location = SL_OBJECT_NORMAL_MATRIX) uniform mat4 normal_matrix;  // inverse transpose of model
layout(location = SL_SSS_VIEW_PROJECTION) uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
    vec4 p = model * vec4(position, 1.0);
    world_position = p.xyz;
    world_normal = mat3(normal_matrix) * normal;
    gl_Position = view_projection * p;
}
