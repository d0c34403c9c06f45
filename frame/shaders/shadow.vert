#version 450 core
// Shadow map pass: depth from the light, and the light's linear depth for the VSM moments.
#include "gl/shaders/object_uniforms.h"
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
layout(location = SL_OBJECT_MODEL) uniform mat4 model;
out float light_depth;
void main() {
    vec4 world = model * vec4(position, 1.0);
    light_depth = dot(world.xyz - frame.light_position.xyz, frame.light_direction.xyz) /
                  frame.light_direction.w;
    gl_Position = frame.light_view_projection * world;
}
